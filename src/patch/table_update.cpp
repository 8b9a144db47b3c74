#include "patch/table_update.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace rad {

namespace {

// The patches of two meshes refined from one base mesh, paired by node: both are numbered in
// key order, so one walk pairs those of equal key ranges. Empty when a mesh is not in key order.
struct PatchMatch {
  std::vector<uint32_t> oldOf;  ///< per new patch, the old one of its node, or kNoPatch
  std::vector<uint32_t> newOf;  ///< per old patch, the new one of its node, or kNoPatch
};

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

// Items put in buckets 0..n-1 by one pass over `sources` in order: each bucket in that order.
template <typename T>
struct Buckets {
  std::vector<uint64_t> start;
  std::vector<T> items;
  std::span<const T> of(size_t b) const {
    return {items.data() + start[b], size_t(start[b + 1] - start[b])};
  }
};

template <typename T, class Each>
Buckets<T> bucketed(size_t n, std::span<const uint32_t> sources, const Each& each) {
  Buckets<T> b;
  b.start.assign(n + 1, 0);
  for (uint32_t s : sources) each(s, [&](uint32_t bucket, const T&) { ++b.start[bucket + 1]; });
  for (size_t i = 0; i < n; ++i) b.start[i + 1] += b.start[i];
  b.items.resize(b.start.back());
  std::vector<uint64_t> next(b.start.begin(), b.start.end() - 1);
  for (uint32_t s : sources)
    each(s, [&](uint32_t bucket, const T& item) { b.items[next[bucket]++] = item; });
  return b;
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

// The entry for `column` of a row sorted by column, 0 if none.
float entryOf(const std::vector<FormFactorEntry>& row, uint32_t column) {
  const auto it = std::partition_point(row.begin(), row.end(),
                                       [&](const FormFactorEntry& e) { return e.column < column; });
  return it != row.end() && it->column == column ? it->value : 0.0f;
}

}  // namespace

std::vector<uint8_t> newPatchesOf(const PatchMesh& before, const PatchMesh& mesh, int levels) {
  const std::optional<PatchMatch> match = matchPatches(before, mesh, levels);
  std::vector<uint8_t> added(mesh.size(), 1);
  if (match)
    for (uint32_t q = 0; q < mesh.size(); ++q) added[q] = match->oldOf[q] == kNoPatch;
  return added;
}

std::optional<FormFactorTable> updatedTable(const SymmetrizedTable& before, const PatchMesh& mesh,
                                            std::span<const uint32_t> exactColumns,
                                            const MasterFormFactorTable::Rows& rows, int levels,
                                            FormFactorTable storage) {
  const std::optional<PatchMatch> match = matchPatches(before.mesh, mesh, levels);
  if (!match || exactColumns.size() != before.exactColumns.size()) return std::nullopt;
  for (size_t k = 0; k < exactColumns.size(); ++k)
    if (match->oldOf[exactColumns[k]] != before.exactColumns[k]) return std::nullopt;
  const std::vector<uint32_t>&oldOf = match->oldOf, &newOf = match->newOf;
  std::vector<uint32_t> added, removed;
  for (uint32_t q = 0; q < mesh.size(); ++q)
    if (oldOf[q] == kNoPatch) added.push_back(q);
  for (uint32_t p = 0; p < before.mesh.size(); ++p)
    if (newOf[p] == kNoPatch) removed.push_back(p);
  auto newRange = [&](uint32_t q) { return mesh.nodeKeys(mesh.patches()[q].node, levels); };
  auto oldRange = [&](uint32_t p) {
    return before.mesh.nodeKeys(before.mesh.patches()[p].node, levels);
  };
  auto area = [&](uint32_t q) { return mesh.patches()[q].area; };
  const ExactColumns* exact = rows.exact ? &*rows.exact : nullptr;
  for (uint32_t q = 0; q < mesh.size(); ++q)
    if (oldOf[q] != kNoPatch && !(exact && exact->isExact[q]) && !rows.hits[q])
      return std::nullopt;  // a kept row's hits not in the master table: no way to update
  std::vector<uint32_t> indexOfAdded(mesh.size(), kNoPatch);
  for (uint32_t a = 0; a < added.size(); ++a) indexOfAdded[added[a]] = a;

  // The new patches over each removed one: [first, last) in `added`.
  std::vector<std::pair<uint32_t, uint32_t>> addedOver(before.mesh.size(), {0, 0});
  for (uint32_t r : removed) {
    const std::span<const uint32_t> over = overlapping(added, newRange, oldRange(r));
    const uint32_t first = uint32_t(over.data() - added.data());
    addedOver[r] = {first, first + uint32_t(over.size())};
  }
  // The new rows' entries for kept patches, by kept patch: (j, F_jq), j ascending.
  const auto seenBy = bucketed<FormFactorEntry>(mesh.size(), added, [&](uint32_t j, auto&& put) {
    for (const FormFactorEntry& e : rows.rows[j])
      if (oldOf[e.column] != kNoPatch) put(e.column, FormFactorEntry{j, e.value});
  });

  // By kept patch, the removed patches its old row held, ascending: from the removed patches' own
  // rows (a symmetrized table holds (i, j) where it holds (j, i)), not from every kept row.
  const auto removedIn = bucketed<uint32_t>(mesh.size(), removed, [&](uint32_t r, auto&& put) {
    for (uint32_t c : before.table.columns(r))
      if (newOf[c] != kNoPatch) put(newOf[c], r);
  });

  // Per kept row q, the new patches it may have entries for: those over the removed patches
  // its old row held (its rays may land in them), and those whose rays found it. For each,
  // F_qj from q's hits in j's key range (or, for an exact row, by reciprocity from j's exact
  // entry), and F_jq.
  struct Pair {
    uint32_t j;
    float fqj, fjq;
  };
  std::vector<std::vector<Pair>> pairs(mesh.size());
  tbb::parallel_for(size_t(0), mesh.size(), [&](size_t qi) {
    const uint32_t q = uint32_t(qi);
    if (oldOf[q] == kNoPatch) return;
    std::vector<uint32_t> over;
    for (uint32_t r : removedIn.of(q))
      for (uint32_t a = addedOver[r].first; a < addedOver[r].second; ++a)
        if (over.empty() || over.back() < added[a]) over.push_back(added[a]);
    const std::span<const FormFactorEntry> seen = seenBy.of(q);
    if (over.empty() && seen.empty()) return;
    const bool exactRow = exact && exact->isExact[q];
    const std::vector<HemisphereHit>* hits = exactRow ? nullptr : rows.hits[q];
    auto hit = hits ? hits->begin() : std::vector<HemisphereHit>::const_iterator{};
    auto fromRow = [&](uint32_t j) {
      if (exactRow) return exactReciprocal(*exact, j, q, area(j), area(q));
      const std::pair<uint64_t, uint64_t> range = newRange(j);
      const uint64_t first = range.first, last = range.second;
      hit = std::partition_point(
          hit, hits->end(), [first](const HemisphereHit& h) { return uint64_t{h.key} < first; });
      float sum = 0.0f;  // in key order, as rowFromHits and mergeByColumn add them
      for (; hit != hits->end() && uint64_t{hit->key} < last; ++hit) sum += hit->weight;
      return sum;
    };
    auto s = seen.begin();
    for (size_t k = 0; k < over.size() || s != seen.end();) {
      const uint32_t j =
          std::min(k < over.size() ? over[k] : kNoPatch, s != seen.end() ? s->column : kNoPatch);
      const float fjq = s != seen.end() && s->column == j ? (s++)->value : 0.0f;
      if (k < over.size() && over[k] == j) ++k;
      pairs[q].push_back({j, fromRow(j), fjq});
    }
  });
  // The kept rows' new entries, and by new patch the kept rows' (q, F_qj, F_jq), q ascending.
  std::vector<std::vector<FormFactorEntry>> keptNew(mesh.size());
  tbb::parallel_for(size_t(0), mesh.size(), [&](size_t q) {
    for (const Pair& e : pairs[q])
      if (const float v = reciprocalMean(e.fqj, e.fjq, area(uint32_t(q)), area(e.j)); v > 0.0f)
        keptNew[q].push_back({e.j, v});
  });
  std::vector<std::vector<Pair>> keptOf(added.size());
  for (uint32_t q = 0; q < mesh.size(); ++q)
    for (const Pair& e : pairs[q]) keptOf[indexOfAdded[e.j]].push_back({q, e.fqj, e.fjq});
  // Between new patches: the union of their rows' columns.
  std::vector<std::vector<uint32_t>> newPartners(added.size());
  for (uint32_t a = 0; a < added.size(); ++a)
    for (const FormFactorEntry& e : rows.rows[added[a]])
      if (const uint32_t b = indexOfAdded[e.column]; b != kNoPatch) {
        newPartners[a].push_back(e.column);
        newPartners[b].push_back(added[a]);
      }
  // A new row: its entries for kept patches and for new ones, in column order.
  std::vector<std::vector<FormFactorEntry>> newRows(added.size());
  tbb::parallel_for(size_t(0), added.size(), [&](size_t a) {
    std::vector<uint32_t>& partners = newPartners[a];
    std::sort(partners.begin(), partners.end());
    partners.erase(std::unique(partners.begin(), partners.end()), partners.end());
    const uint32_t j = added[a];
    auto kept = keptOf[a].begin();
    auto emitKeptBelow = [&](uint32_t column) {
      for (; kept != keptOf[a].end() && kept->j < column; ++kept)
        if (const float v = reciprocalMean(kept->fjq, kept->fqj, area(j), area(kept->j)); v > 0.0f)
          newRows[a].push_back({kept->j, v});
    };
    for (uint32_t k : partners) {
      emitKeptBelow(k);
      const float v =
          reciprocalMean(entryOf(rows.rows[j], k), entryOf(rows.rows[k], j), area(j), area(k));
      if (v > 0.0f) newRows[a].push_back({k, v});
    }
    emitKeptBelow(kNoPatch);
  });

  // Every row in the new numbering: a kept row's entries for kept patches renumbered, merged
  // with its new ones; a new row's entries with kept and new patches, merged. Counted, then
  // written in place.
  auto forEachEntry = [&](uint32_t q, auto&& emit) {
    const uint32_t p = oldOf[q];
    if (p == kNoPatch) {
      for (const FormFactorEntry& e : newRows[indexOfAdded[q]]) emit(e);
      return;
    }
    const auto columns = before.table.columns(p);
    const auto values = before.table.values(p);
    auto fresh = keptNew[q].begin();
    for (size_t e = 0; e < columns.size(); ++e) {
      const uint32_t c = newOf[columns[e]];
      if (c == kNoPatch) continue;
      for (; fresh != keptNew[q].end() && fresh->column < c; ++fresh) emit(*fresh);
      emit(FormFactorEntry{c, values[e]});
    }
    for (; fresh != keptNew[q].end(); ++fresh) emit(*fresh);
  };
  std::vector<uint64_t> counts(mesh.size());
  tbb::parallel_for(size_t(0), mesh.size(), [&](size_t q) {
    const uint32_t p = oldOf[q];
    counts[q] = p == kNoPatch
                    ? newRows[indexOfAdded[q]].size()
                    : before.table.columns(p).size() - removedIn.of(q).size() + keptNew[q].size();
  });
  FormFactorTable table = FormFactorTable::withRowSizes(counts, std::move(storage));
  tbb::parallel_for(size_t(0), mesh.size(), [&](size_t q) {
    const std::span<uint32_t> columns = table.rowColumns(q);
    const std::span<float> values = table.rowValues(q);
    size_t at = 0;
    forEachEntry(uint32_t(q), [&](const FormFactorEntry& e) {
      columns[at] = e.column;
      values[at++] = e.value;
    });
  });
  return table;
}

}  // namespace rad
