#include "patch/table_update.h"

#include <tbb/parallel_for.h>

#include <algorithm>

#include "core/buckets.h"

namespace rad {

std::optional<PatchMatch> matchPatches(const PatchMesh& before, const PatchMesh& mesh, int levels) {
  PatchMatch m{std::vector<uint32_t>(mesh.size(), kNoPatch),
               std::vector<uint32_t>(before.size(), kNoPatch)};
  uint64_t lastA = 0, lastB = 0;
  for (uint32_t a = 0, b = 0; a < before.size() && b < mesh.size();) {
    const auto ka = before.nodeKeys(before.patches()[a].node, levels);
    const auto kb = mesh.nodeKeys(mesh.patches()[b].node, levels);
    if (ka.first < lastA || kb.first < lastB) return std::nullopt;
    lastA = ka.first;
    lastB = kb.first;
    if (ka == kb) {
      m.oldOf[b] = a;
      m.newOf[a] = b;
    }
    if (ka.second <= kb.second) ++a;
    if (kb.second <= ka.second) ++b;
  }
  return m;
}

std::vector<uint8_t> PatchMatch::fresh() const {
  std::vector<uint8_t> added(oldOf.size());
  for (size_t q = 0; q < oldOf.size(); ++q) added[q] = oldOf[q] == kNoPatch;
  return added;
}

namespace {

// The patches among `patches` (ascending, so in key order) whose key ranges meet [first, last).
template <class RangeOf>
std::span<const uint32_t> overlapping(std::span<const uint32_t> patches, const RangeOf& rangeOf,
                                      std::pair<uint64_t, uint64_t> range) {
  const auto begin = std::partition_point(
      patches.begin(), patches.end(), [&](uint32_t p) { return rangeOf(p).second <= range.first; });
  auto end = begin;
  while (end != patches.end() && rangeOf(*end).first < range.second) ++end;
  return {begin, end};
}

// F_ej of an exact patch e for a patch j, by reciprocity from j's exact entry for e, as
// exactColumns computes its rows.
float exactReciprocal(const ExactColumns& exact, uint32_t j, uint32_t e, float areaJ, float areaE) {
  const std::vector<FormFactorEntry>& row = exact.toExact[j];
  const auto it = std::partition_point(row.begin(), row.end(),
                                       [&](const FormFactorEntry& x) { return x.column < e; });
  if (it == row.end() || it->column != e || !(areaE > 0.0f)) return 0.0f;
  return it->value * areaJ / areaE;
}

// The steps of updatedTable, over the two meshes' patches paired by node.
class TableUpdate {
 public:
  TableUpdate(const SymmetrizedTable& before, const PatchMesh& mesh,
              const MasterFormFactorTable::Rows& rows, int levels, PatchMatch match)
      : before_(before),
        mesh_(mesh),
        rows_(rows),
        levels_(levels),
        exact_(rows.exact ? &*rows.exact : nullptr),
        oldOf_(std::move(match.oldOf)),
        newOf_(std::move(match.newOf)),
        indexOfAdded_(mesh.size(), kNoPatch) {
    for (uint32_t q = 0; q < mesh.size(); ++q)
      if (oldOf_[q] == kNoPatch) {
        indexOfAdded_[q] = uint32_t(added_.size());
        added_.push_back(q);
      }
    for (uint32_t p = 0; p < before.mesh.size(); ++p)
      if (newOf_[p] == kNoPatch) removed_.push_back(p);
    for (uint32_t q : added_) addedRange_.push_back(newRange(q));
  }

  /// Every kept row that is not exact has its hits in the master table.
  bool keptRowsHaveHits() const {
    for (uint32_t q = 0; q < mesh_.size(); ++q)
      if (oldOf_[q] != kNoPatch && !isExact(q) && !rows_.hits[q]) return false;
    return true;
  }
  void pairKeptWithNew();
  void makeNewRows();
  FormFactorTable write(FormFactorTable storage) const;

 private:
  // A kept row q's estimates for a new patch j: F_qj by q's rays, F_jq by j's.
  struct Pair {
    uint32_t patch;  ///< j, or q where listed by new patch
    float fqj, fjq;
  };

  std::pair<uint64_t, uint64_t> newRange(uint32_t q) const {
    return mesh_.nodeKeys(mesh_.patches()[q].node, levels_);
  }
  std::pair<uint64_t, uint64_t> oldRange(uint32_t p) const {
    return before_.mesh.nodeKeys(before_.mesh.patches()[p].node, levels_);
  }
  float area(uint32_t q) const { return mesh_.patches()[q].coveredArea(); }
  bool isExact(uint32_t q) const { return exact_ && exact_->isExact[q]; }
  std::vector<uint32_t> newPatchesOver(std::span<const uint32_t> removedSeen) const;
  void pairRow(uint32_t q, std::span<const uint32_t> removedSeen,
               std::span<const FormFactorEntry> seen);

  const SymmetrizedTable& before_;
  const PatchMesh& mesh_;
  const MasterFormFactorTable::Rows& rows_;
  int levels_;
  const ExactColumns* exact_;
  std::vector<uint32_t> oldOf_, newOf_;  ///< per new patch its old one, per old its new one
  std::vector<uint32_t> added_, removed_, indexOfAdded_;
  std::vector<std::pair<uint64_t, uint64_t>> addedRange_;  ///< per new patch, its key range
  /// Per removed patch, the new patches over it: [first, last) in added_.
  std::vector<std::pair<uint32_t, uint32_t>> addedOver_;
  std::vector<std::vector<Pair>> pairsOfKept_;         ///< per kept row, by new patch
  std::vector<std::vector<FormFactorEntry>> keptNew_;  ///< per kept row, its new entries
  std::vector<uint64_t> removedCount_;                 ///< per kept row, removed columns
  std::vector<std::vector<FormFactorEntry>> newRows_;  ///< per new patch, its row
};

// The new patches a kept row may have entries for because its rays may land in them: those over
// the removed patches its old row held (`removedSeen`), ascending.
std::vector<uint32_t> TableUpdate::newPatchesOver(std::span<const uint32_t> removedSeen) const {
  std::vector<uint32_t> over;
  for (uint32_t r : removedSeen)
    for (uint32_t a = addedOver_[r].first; a < addedOver_[r].second; ++a)
      if (over.empty() || over.back() < added_[a]) over.push_back(added_[a]);
  return over;
}

// Kept row q with every new patch j its rays may find or whose rays found it (`seen`: (j,
// F_jq)): F_qj from q's hits in j's key range, walked once in key order (or, for an exact row,
// by reciprocity from j's exact entry), and q's new entries.
void TableUpdate::pairRow(uint32_t q, std::span<const uint32_t> removedSeen,
                          std::span<const FormFactorEntry> seen) {
  const std::vector<uint32_t> over = newPatchesOver(removedSeen);
  if (over.empty() && seen.empty()) return;
  const std::vector<HemisphereHit>* hits = isExact(q) ? nullptr : rows_.hits[q];
  auto hit = hits ? hits->begin() : std::vector<HemisphereHit>::const_iterator{};
  auto fromRow = [&](uint32_t j) {
    if (!hits) return exactReciprocal(*exact_, j, q, area(j), area(q));
    const std::pair<uint64_t, uint64_t> range = addedRange_[indexOfAdded_[j]];
    const uint64_t first = range.first, last = range.second;
    // Stepped, not searched: the new patches come in key order, often more of them than hits.
    while (hit != hits->end() && uint64_t{hit->key} < first) ++hit;
    float sum = 0.0f;  // in key order, as rowFromHits and mergeByColumn add them
    for (; hit != hits->end() && uint64_t{hit->key} < last; ++hit) sum += hit->weight;
    return sum;
  };
  pairsOfKept_[q].reserve(over.size() + seen.size());
  auto s = seen.begin();
  for (size_t k = 0; k < over.size() || s != seen.end();) {
    const uint32_t j =
        std::min(k < over.size() ? over[k] : kNoPatch, s != seen.end() ? s->column : kNoPatch);
    const float fjq = s != seen.end() && s->column == j ? (s++)->value : 0.0f;
    if (k < over.size() && over[k] == j) ++k;
    const Pair pair{j, fromRow(j), fjq};
    pairsOfKept_[q].push_back(pair);
    if (const float v = reciprocalMean(pair.fqj, pair.fjq, area(q), area(j)); v > 0.0f)
      keptNew_[q].push_back({j, v});
  }
}

void TableUpdate::pairKeptWithNew() {
  addedOver_.assign(before_.mesh.size(), {0, 0});
  for (uint32_t r : removed_) {
    const std::span<const uint32_t> over = overlapping(
        added_, [&](uint32_t q) { return addedRange_[indexOfAdded_[q]]; }, oldRange(r));
    const uint32_t first = uint32_t(over.data() - added_.data());
    addedOver_[r] = {first, first + uint32_t(over.size())};
  }
  // By kept patch: the new rows' entries for it, (j, F_jq) with j ascending; the removed patches
  // its old row held, ascending, from the removed patches' own rows (a symmetrized table holds
  // (i, j) where it holds (j, i)) rather than from every kept row.
  const auto seenBy = bucketed<FormFactorEntry>(mesh_.size(), added_, [&](uint32_t j, auto&& put) {
    for (const FormFactorEntry& e : rows_.rows[j])
      if (oldOf_[e.column] != kNoPatch) put(e.column, FormFactorEntry{j, e.value});
  });
  const auto removedIn = bucketed<uint32_t>(mesh_.size(), removed_, [&](uint32_t r, auto&& put) {
    for (uint32_t c : before_.table.columns(r))
      if (newOf_[c] != kNoPatch) put(newOf_[c], r);
  });
  pairsOfKept_.assign(mesh_.size(), {});
  keptNew_.assign(mesh_.size(), {});
  removedCount_.assign(mesh_.size(), 0);
  tbb::parallel_for(size_t(0), mesh_.size(), [&](size_t q) {
    if (oldOf_[q] == kNoPatch) return;
    removedCount_[q] = removedIn.of(q).size();
    pairRow(uint32_t(q), removedIn.of(q), seenBy.of(q));
  });
}

// A new row: its entries for kept patches (their pairs, by reciprocity) and for new ones (the
// union of the new rows' columns), in column order.
void TableUpdate::makeNewRows() {
  std::vector<uint32_t> kept;
  for (uint32_t q = 0; q < mesh_.size(); ++q)
    if (!pairsOfKept_[q].empty()) kept.push_back(q);
  const auto keptOf = bucketed<Pair>(added_.size(), kept, [&](uint32_t q, auto&& put) {
    for (const Pair& e : pairsOfKept_[q]) put(indexOfAdded_[e.patch], Pair{q, e.fqj, e.fjq});
  });
  // By new patch k, the new rows' entries for it: (j, F_jk), j ascending.
  const auto newSeenBy =
      bucketed<FormFactorEntry>(added_.size(), added_, [&](uint32_t j, auto&& put) {
        for (const FormFactorEntry& e : rows_.rows[j])
          if (const uint32_t b = indexOfAdded_[e.column]; b != kNoPatch)
            put(b, FormFactorEntry{j, e.value});
      });
  newRows_.assign(added_.size(), {});
  tbb::parallel_for(size_t(0), added_.size(), [&](size_t a) {
    const uint32_t j = added_[a];
    const std::span<const Pair> pairs = keptOf.of(a);
    newRows_[a].reserve(pairs.size() + rows_.rows[j].size() + newSeenBy.of(a).size());
    auto pair = pairs.begin();
    auto keptBelow = [&](uint32_t column) {
      for (; pair != pairs.end() && pair->patch < column; ++pair)
        if (const float v = reciprocalMean(pair->fjq, pair->fqj, area(j), area(pair->patch));
            v > 0.0f)
          newRows_[a].push_back({pair->patch, v});
    };
    // The new patches k in row j (F_jk) or whose rows hold j (F_kj), merged in column order.
    const std::vector<FormFactorEntry>& row = rows_.rows[j];
    const std::span<const FormFactorEntry> seen = newSeenBy.of(a);
    auto own = row.begin();
    auto next = [&] {
      while (own != row.end() && indexOfAdded_[own->column] == kNoPatch) ++own;
    };
    next();
    for (auto s = seen.begin(); own != row.end() || s != seen.end();) {
      const uint32_t k = std::min(own != row.end() ? own->column : kNoPatch,
                                  s != seen.end() ? s->column : kNoPatch);
      float fjk = 0.0f, fkj = 0.0f;
      if (own != row.end() && own->column == k) {
        fjk = own->value;
        ++own;
        next();
      }
      if (s != seen.end() && s->column == k) fkj = (s++)->value;
      keptBelow(k);
      if (const float v = reciprocalMean(fjk, fkj, area(j), area(k)); v > 0.0f)
        newRows_[a].push_back({k, v});
    }
    keptBelow(kNoPatch);
  });
}

// Every row in the new numbering: a kept row's entries for kept patches renumbered, merged with
// its new ones; a new row as made. Sized, then written in place.
FormFactorTable TableUpdate::write(FormFactorTable storage) const {
  std::vector<uint64_t> counts(mesh_.size());
  tbb::parallel_for(size_t(0), mesh_.size(), [&](size_t q) {
    const uint32_t p = oldOf_[q];
    counts[q] = p == kNoPatch
                    ? newRows_[indexOfAdded_[q]].size()
                    : before_.table.columns(p).size() - removedCount_[q] + keptNew_[q].size();
  });
  FormFactorTable table = FormFactorTable::withRowSizes(counts, std::move(storage));
  tbb::parallel_for(size_t(0), mesh_.size(), [&](size_t q) {
    const std::span<uint32_t> columns = table.rowColumns(q);
    const std::span<float> values = table.rowValues(q);
    size_t at = 0;
    auto emit = [&](const FormFactorEntry& e) {
      columns[at] = e.column;
      values[at++] = e.value;
    };
    const uint32_t p = oldOf_[q];
    if (p == kNoPatch) {
      for (const FormFactorEntry& e : newRows_[indexOfAdded_[q]]) emit(e);
      return;
    }
    const auto oldColumns = before_.table.columns(p);
    const auto oldValues = before_.table.values(p);
    auto fresh = keptNew_[q].begin();
    for (size_t e = 0; e < oldColumns.size(); ++e) {
      const uint32_t c = newOf_[oldColumns[e]];
      if (c == kNoPatch) continue;
      for (; fresh != keptNew_[q].end() && fresh->column < c; ++fresh) emit(*fresh);
      emit(FormFactorEntry{c, oldValues[e]});
    }
    for (; fresh != keptNew_[q].end(); ++fresh) emit(*fresh);
  });
  return table;
}

}  // namespace

std::optional<FormFactorTable> updatedTable(const SymmetrizedTable& before, const PatchMesh& mesh,
                                            PatchMatch match,
                                            std::span<const uint32_t> exactColumns,
                                            const MasterFormFactorTable::Rows& rows, int levels,
                                            FormFactorTable storage) {
  if (exactColumns.size() != before.exactColumns.size()) return std::nullopt;
  for (size_t k = 0; k < exactColumns.size(); ++k)
    if (match.oldOf[exactColumns[k]] != before.exactColumns[k]) return std::nullopt;
  TableUpdate update(before, mesh, rows, levels, std::move(match));
  if (!update.keptRowsHaveHits()) return std::nullopt;
  update.pairKeptWithNew();
  update.makeNewRows();
  return update.write(std::move(storage));
}

}  // namespace rad
