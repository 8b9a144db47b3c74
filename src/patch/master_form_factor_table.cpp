#include "patch/master_form_factor_table.h"

#include <fmt/format.h>
#include <radiosity/error.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cstring>
#include <unordered_map>

#include "core/checksummed_file.h"
#include "core/progress_ticker.h"
#include "patch/row_exchange.h"

namespace rad {

namespace {

// The patch whose node covers each finest key. A root whose patches all lie at one depth (most,
// away from the lights) maps a key by arithmetic: its patches are numbered in the order of their
// paths. Others search their own patches' key ranges, which tile the root.
class PatchOfKey {
 public:
  PatchOfKey(const PatchMesh& mesh, int levels) : roots_(mesh.roots().size()) {
    for (uint32_t p = 0; p < mesh.size(); ++p) {
      const PatchNode& node = mesh.nodeOf(p);
      Root& r = roots_[node.root];
      const auto [first, last] = mesh.nodeKeys(mesh.patches()[p].node, levels);
      if (r.ranges.empty()) r.shift = int(std::countr_zero(last - first));
      if (int(std::countr_zero(last - first)) != r.shift) r.uniform = false;
      r.ranges.push_back({first, last, p});
    }
    for (Root& r : roots_)
      std::sort(r.ranges.begin(), r.ranges.end(),
                [](const Range& a, const Range& b) { return a.first < b.first; });
  }
  uint32_t operator()(uint64_t key) const {
    const Root& r = roots_[key >> 32];
    if (r.ranges.empty()) return kNoPatch;
    if (r.uniform) {
      const uint64_t k = (key - r.ranges.front().first) >> r.shift;
      return k < r.ranges.size() ? r.ranges[k].patch : kNoPatch;
    }
    auto it = std::upper_bound(r.ranges.begin(), r.ranges.end(), key,
                               [](uint64_t k, const Range& range) { return k < range.first; });
    if (it == r.ranges.begin()) return kNoPatch;
    --it;
    return key < it->last ? it->patch : kNoPatch;
  }

 private:
  struct Range {
    uint64_t first, last;
    uint32_t patch;
  };
  struct Root {
    std::vector<Range> ranges;  ///< by first key
    int shift = 0;              ///< log2 of a patch's key count, when uniform
    bool uniform = true;
  };
  std::vector<Root> roots_;
};

// Rays of a node refinement made draw from a stream apart from every base patch's.
constexpr uint64_t kRefinedStreams = 1ull << 63;

}  // namespace

MasterFormFactorTable::MasterFormFactorTable(int levels, int rays, uint64_t seed)
    : levels_(levels), rays_(rays), seed_(seed) {}

namespace {

// The rows each process cast (its block of `hits`) to every process, each then done.
void exchangeCastRows(const ProcessShare& processes, std::vector<std::vector<HemisphereHit>>& hits,
                      std::vector<std::atomic<uint8_t>>& done) {
  exchangeRows(processes, RowShare::Blocks, hits);
  for (auto& d : done) d.store(1, std::memory_order_release);
}

}  // namespace

MasterFormFactorTable::Rows MasterFormFactorTable::rowsFor(const PatchMesh& mesh,
                                                           const RayCaster& caster,
                                                           const std::vector<uint32_t>& basePatchOf,
                                                           const FormFactorSettings& ff,
                                                           const ProgressCallback& progress,
                                                           std::span<const uint8_t> wanted) {
  auto isWanted = [&](uint32_t p) { return wanted.empty() || wanted[p]; };
  auto address = [&](uint32_t p) { return mesh.nodeAddress(mesh.patches()[p].node); };
  auto streamOf = [&](uint32_t p) {
    const uint32_t node = mesh.patches()[p].node;
    return node < basePatchOf.size() && basePatchOf[node] != kNoPatch
               ? uint64_t(basePatchOf[node])
               : kRefinedStreams | mesh.nodeAddress(node);
  };
  // The emitters' exact entries are kept by emitter address, for one set of emitter nodes.
  std::unordered_map<uint64_t, uint32_t> emitterPatch;
  uint64_t exactSet = 0x9e3779b97f4a7c15ull;
  for (uint32_t j : ff.exactColumns) {
    emitterPatch[address(j)] = j;
    exactSet = (exactSet ^ address(j)) * 0x100000001b3ull;
  }
  std::vector<uint8_t> cast(mesh.size(), 0), exactCast(mesh.size(), 0);
  const ExactRowStore store{
      [&](uint32_t p) -> std::optional<std::vector<FormFactorEntry>> {
        std::lock_guard lock(mutex_);
        const auto it = rows_.find(address(p));
        if (it == rows_.end() || !it->second.hasExact || it->second.exactSet != exactSet)
          return std::nullopt;
        std::vector<FormFactorEntry> row;
        for (const HemisphereHit& e : it->second.exact)
          row.push_back({emitterPatch.at(uint64_t{e.key}), e.weight});
        std::sort(row.begin(), row.end(), [](auto& a, auto& b) { return a.column < b.column; });
        return row;
      },
      [&](uint32_t p, const std::vector<FormFactorEntry>&) { exactCast[p] = 1; }, streamOf};
  Rows out;
  // An exact patch's row wanted needs every patch's exact entries (its row is their reciprocal).
  const bool exactRowWanted = std::any_of(ff.exactColumns.begin(), ff.exactColumns.end(),
                                          [&](uint32_t j) { return isWanted(j); });
  out.exact =
      exactColumns(mesh, caster, ff, &store, exactRowWanted ? std::span<const uint8_t>{} : wanted);
  const ExactColumns* exact = out.exact ? &*out.exact : nullptr;

  // Hemisphere rows not kept are cast (in parallel), then every row is assembled from its hits.
  std::vector<uint32_t> missing;
  std::vector<const std::vector<HemisphereHit>*> hitsOf(mesh.size(), nullptr);
  {
    std::lock_guard lock(mutex_);
    for (uint32_t p = 0; p < mesh.size(); ++p) {
      if (exact && exact->isExact[p]) continue;
      const auto it = rows_.find(address(p));
      if (it != rows_.end() && it->second.hasHits)
        hitsOf[p] = &it->second.hits;
      else if (isWanted(p))
        missing.push_back(p);
    }
  }
  const HitKey keyOf = [&](uint32_t triangle, bool front, const Vec3& at) {
    return mesh.finestKey(triangle, front, at, levels_);
  };
  // The emitters' exact entries computed above, into their rows (under the lock).
  auto keepExactRows = [&] {
    for (uint32_t p = 0; exact && p < mesh.size(); ++p) {
      if (!exactCast[p]) continue;
      cast[p] = 1;
      changeRow(address(p), [&](MasterRow& row) {
        row.exactSet = exactSet;
        row.hasExact = true;
        row.exact.clear();
        for (const FormFactorEntry& e : exact->toExact[p])
          row.exact.push_back({address(e.column), e.value});
      });
    }
  };
  std::vector<std::vector<HemisphereHit>> hits(missing.size());
  std::vector<std::atomic<uint8_t>> done(missing.size());
  // The rows cast so far (each depends on its own random stream alone) into the table, and the
  // table to disk, so that a solve stopped or killed now casts only the rest when run again.
  auto keepRowsCast = [&] {
    {
      std::lock_guard lock(mutex_);
      for (size_t i = 0; i < missing.size(); ++i) {
        if (!done[i].load(std::memory_order_acquire)) continue;
        changeRow(address(missing[i]), [&](MasterRow& row) {
          if (!row.hasHits) row.hits = hits[i];
          row.hasHits = true;
        });
      }
      keepExactRows();
    }
    return !diskFile_.empty() && save(diskFile_, diskKey_).empty();
  };
  const double interval = checkpointIntervalSeconds();
  std::mutex saving;
  auto lastSave = std::chrono::steady_clock::now();
  // Split among processes, each casts a block of the missing rows, and the blocks are exchanged
  // below: every process then holds every row (each row's rays are its own stream's, whoever
  // casts it), so all of them assemble and solve the same table.
  const auto [first, last] = ff.processes.block(missing.size());
  ProgressTicker ticker(progress, last - first);
  tbb::parallel_for(first, last, [&](size_t i) {
    if (ticker.cancelled()) return;
    hits[i] = hemisphereHits(mesh, caster, missing[i], rays_, seed_, streamOf(missing[i]), keyOf);
    done[i].store(1, std::memory_order_release);
    ticker.tick();
    if (diskFile_.empty()) return;
    std::unique_lock lock(saving, std::try_to_lock);
    const auto now = std::chrono::steady_clock::now();
    if (!lock.owns_lock() || std::chrono::duration<double>(now - lastSave).count() < interval)
      return;
    keepRowsCast();
    lastSave = now;
  });
  if (ticker.cancelled()) {
    if (!keepRowsCast()) throw Cancelled();
    throw Cancelled(
        fmt::format("the form-factor rows cast so far are kept in {}: solved again, "
                    "it casts only the rest",
                    diskFile_.string()));
  }
  if (ff.processes.split()) exchangeCastRows(ff.processes, hits, done);
  {
    // Another solve may have cast the same row meanwhile: the first one kept stays.
    std::lock_guard lock(mutex_);
    for (size_t i = 0; i < missing.size(); ++i) {
      changeRow(address(missing[i]), [&](MasterRow& row) {
        if (!row.hasHits) row.hits = std::move(hits[i]);
        row.hasHits = true;
        hitsOf[missing[i]] = &row.hits;
      });
      cast[missing[i]] = 1;
    }
    keepExactRows();
  }
  out.computed = size_t(std::count(cast.begin(), cast.end(), 1));
  const size_t made =
      wanted.empty() ? mesh.size() : size_t(std::count(wanted.begin(), wanted.end(), 1));
  out.reused = made - out.computed;
  const PatchOfKey patchOf(mesh, levels_);
  out.rows.resize(mesh.size());
  tbb::parallel_for(size_t(0), mesh.size(), [&](size_t i) {
    const uint32_t p = uint32_t(i);
    if (!isWanted(p)) return;
    out.rows[i] = exact && exact->isExact[p] ? exactPatchRow(*exact, p)
                                             : rowFromHits(*hitsOf[p], p, patchOf, exact);
  });
  out.hits = std::move(hitsOf);
  return out;
}

size_t MasterFormFactorTable::rows() const {
  std::lock_guard lock(mutex_);
  return rows_.size();
}

size_t MasterFormFactorTable::memoryBytes() const {
  std::lock_guard lock(mutex_);
  return bytes_;
}

size_t MasterFormFactorTable::rowBytes(const MasterRow& row) {
  return 48 + (row.hits.capacity() + row.exact.capacity()) * sizeof(HemisphereHit);
}

std::string MasterFormFactorTable::load(const std::filesystem::path& file,
                                        const FormFactorCacheKey& key) {
  MasterRowsLoad loaded = loadMasterRows(file, key);
  if (loaded.rows) {
    std::lock_guard lock(mutex_);
    for (auto& [address, row] : *loaded.rows) {
      sortByKey(row.hits);  // a file from before rows were kept sorted
      if (const auto [it, inserted] = rows_.try_emplace(address, std::move(row)); inserted)
        bytes_ += rowBytes(it->second);
    }
  }
  return loaded.warning;
}

std::string MasterFormFactorTable::save(const std::filesystem::path& file,
                                        const FormFactorCacheKey& key) const {
  std::lock_guard lock(mutex_);
  return saveMasterRows(file, key, rows_);
}

void MasterFormFactorTable::keepOnDisk(const std::filesystem::path& file,
                                       const FormFactorCacheKey& key) {
  diskFile_ = file;
  diskKey_ = key;
}

}  // namespace rad
