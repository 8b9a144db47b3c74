#pragma once
// The three ways to estimate the form factors between patches. Each returns one row of
// (column, F) entries per patch, sorted by column with each column once, for
// FormFactorTable::fromRows.
//   hemisphere: rays from stratified points on patch i in stratified cosine-weighted directions;
//               the fraction landing on each patch j is F_ij (cost: patches x rays).
//   pairwise:   for each facing pair, random point pairs averaging cos cos / (pi r^2) times
//               visibility; one geometric term serves both F_ij and F_ji (cost: patches^2 x pairs).
//   exact:      the exact unoccluded point-to-polygon factor at points of patch i, times the
//               visibility of patch j from each point by a sample ray (cost: patches^2 x points).

#include <radiosity/patch_radiosity.h>
#include <radiosity/process_share.h>
#include <radiosity/progress.h>
#include <radiosity/ray_caster.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "patch/form_factor_table.h"
#include "patch/patch_mesh.h"

namespace rad {

using FormFactorEstimator = PatchFormFactorEstimator;

struct FormFactorSettings {
  FormFactorEstimator estimator = FormFactorEstimator::Hemisphere;
  /// hemisphere: rays per patch (rounded up to a square); pairwise: point pairs per patch pair;
  /// exact: points per patch (rounded up to a square), each with one visibility ray per patch.
  int rays = 256;
  uint64_t seed = 1;
  /// hemisphere: patches whose columns are computed exactly instead (the emitters, see
  /// ExactColumns), ascending; empty: none.
  std::vector<uint32_t> exactColumns = {};
  /// hemisphere, with the master table: the processes the rows to cast are split among (each
  /// casts a block, and all get every row; process_share.h).
  ProcessShare processes = {};
};

using FormFactorRows = std::vector<std::vector<FormFactorEntry>>;

/// The columns of a few patches (the emitters) by the exact estimator, for the hemisphere one:
/// a small light is found by few of a patch's rays (a 2% solid angle by 5 of 256), so its light
/// on each patch varies by tens of percent from patch to patch (a mottled picture), while the
/// exact kernel with one visibility ray per point is exact wherever the light is wholly seen or
/// hidden. The rows of those patches follow from their columns by reciprocity, so that the
/// table's symmetrization averages equal values.
struct ExactColumns {
  std::vector<uint8_t> isExact;  ///< per patch: its column is exact
  FormFactorRows toExact;        ///< per patch i: (j, F_ij) for the exact columns j
  FormFactorRows exactRows;      ///< per exact patch j: (i, F_ji = F_ij A_i / A_j); else empty
};
/// Points per patch for the exact columns (a 4 x 4 midpoint rule).
constexpr int kExactColumnPoints = 16;
/// Where exactColumns() finds rows computed before and puts those it computes: `known(i)` gives
/// patch i's exact entries (ascending columns) if kept, `computed(i, row)` takes a new one (called
/// from many threads, each i once), `streamOf(i)` names patch i's random stream.
struct ExactRowStore {
  std::function<std::optional<std::vector<FormFactorEntry>>(uint32_t patch)> known;
  std::function<void(uint32_t patch, const std::vector<FormFactorEntry>& row)> computed;
  std::function<uint64_t(uint32_t patch)> streamOf;
};
/// Computes settings.exactColumns for every patch (those `store` does not know); nullopt when
/// there are none. `wanted`: per patch, whether its exact entries are wanted (empty: all); the
/// others' stay empty, and so do exactRows unless all are wanted. Thread-safe.
std::optional<ExactColumns> exactColumns(const PatchMesh& mesh, const RayCaster& caster,
                                         const FormFactorSettings& settings,
                                         const ExactRowStore* store = nullptr,
                                         std::span<const uint8_t> wanted = {});

/// One ray of the hemisphere estimator that found a surface: what it hit, as a key, and its
/// share of the row (the sample's area weight over the rays cast). Packed to 12 bytes: the
/// master table keeps one per ray cast.
#pragma pack(push, 4)
struct HemisphereHit {
  uint64_t key = 0;
  float weight = 0.0f;
};
#pragma pack(pop)
static_assert(sizeof(HemisphereHit) == 12);
/// The key of a hit (triangle, side, point), or kNoKey for none (the back of a one-sided face).
using HitKey = std::function<uint64_t(uint32_t triangle, bool frontFace, const Vec3& point)>;
/// The rays of patch `patch`'s row, in the order cast: stratified points and cosine directions
/// drawn from the random stream (seed, stream). Thread-safe.
std::vector<HemisphereHit> hemisphereHits(const PatchMesh& mesh, const RayCaster& caster,
                                          uint32_t patch, int rays, uint64_t seed, uint64_t stream,
                                          const HitKey& keyOf);
/// Sorts a row by column and adds up repeated columns: rows leave the estimators so.
void mergeByColumn(std::vector<FormFactorEntry>& row);
/// Orders hits by key (stable: the same sums whatever the order they came in), which puts a
/// row's entries in patch order (patches are numbered in key order), so that rows are merged
/// without sorting.
void sortByKey(std::vector<HemisphereHit>& hits);
/// The row of `patch` from its rays' hits (sorted by key), each key mapped by `patchOf` to the
/// patch it lies on (kNoPatch: none), with the exact columns `exact` (if any) in place of what the
/// rays find there.
template <class PatchOf>
std::vector<FormFactorEntry> rowFromHits(std::span<const HemisphereHit> hits, uint32_t patch,
                                         const PatchOf& patchOf, const ExactColumns* exact) {
  std::vector<FormFactorEntry> row;
  row.reserve(hits.size());
  for (const HemisphereHit& h : hits) {
    const uint32_t j = patchOf(h.key);
    // What lands on an exact column is left to its exact value.
    if (j != kNoPatch && j != patch && !(exact && exact->isExact[j])) row.push_back({j, h.weight});
  }
  if (exact) {
    const size_t fromHits = row.size();
    row.insert(row.end(), exact->toExact[patch].begin(), exact->toExact[patch].end());
    std::inplace_merge(
        row.begin(), row.begin() + long(fromHits), row.end(),
        [](const FormFactorEntry& a, const FormFactorEntry& b) { return a.column < b.column; });
  }
  mergeByColumn(row);
  return row;
}
/// The row of an exact patch (an emitter): its exact column's entries by reciprocity.
std::vector<FormFactorEntry> exactPatchRow(const ExactColumns& exact, uint32_t patch);

/// One row by hemisphere ray casting (entries merged by column), with the exact columns
/// `exact` (if any) in place of what its rays find there. Thread-safe.
std::vector<FormFactorEntry> hemisphereRow(const PatchMesh& mesh, const RayCaster& caster,
                                           uint32_t patch, int rays, uint64_t seed,
                                           const ExactColumns* exact = nullptr);

/// Every row by settings.estimator, the one place that maps the kind to its estimator (below).
/// Throws rad::Cancelled if `progress` returns false.
FormFactorRows estimateFormFactors(const PatchMesh& mesh, const RayCaster& caster,
                                   const FormFactorSettings& settings,
                                   const ProgressCallback& progress);

/// Every row by one estimator, whatever settings.estimator says. Throws rad::Cancelled if
/// `progress` returns false.
FormFactorRows hemisphereFormFactors(const PatchMesh& mesh, const RayCaster& caster,
                                     const FormFactorSettings& settings,
                                     const ProgressCallback& progress);
FormFactorRows pairwiseFormFactors(const PatchMesh& mesh, const RayCaster& caster,
                                   const FormFactorSettings& settings,
                                   const ProgressCallback& progress);
FormFactorRows exactFormFactors(const PatchMesh& mesh, const RayCaster& caster,
                                const FormFactorSettings& settings,
                                const ProgressCallback& progress);

}  // namespace rad
