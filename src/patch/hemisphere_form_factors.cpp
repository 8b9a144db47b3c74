// Form factors by ray casting from the patch (the "hemisphere" or Monte Carlo ray-shooting
// estimator): Cohen and Wallace, "Radiosity and Realistic Image Synthesis" (1993), section
// 4.9.4; P. Shirley, "Radiosity via ray tracing", Graphics Gems II (1991). A cosine-weighted
// direction from a uniform point of patch i lands on patch j with probability F_ij. Points and
// directions are each stratified (jittered grids), their strata paired by a random permutation.
// The emitters' columns can be computed exactly instead (ExactColumns): direct light without noise.
#include <radiosity/error.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/progress_ticker.h"
#include "core/rng.h"
#include "geometry/sampling.h"
#include "patch/form_factor_estimators.h"

namespace rad {

void sortByKey(std::vector<HemisphereHit>& hits) {
  const auto byKey = [](const HemisphereHit& a, const HemisphereHit& b) {
    return uint64_t{a.key} < uint64_t{b.key};
  };
  if (!std::is_sorted(hits.begin(), hits.end(), byKey))
    std::stable_sort(hits.begin(), hits.end(), byKey);
}

void mergeByColumn(std::vector<FormFactorEntry>& row) {
  const auto byColumn = [](const FormFactorEntry& a, const FormFactorEntry& b) {
    return a.column < b.column;
  };
  if (!std::is_sorted(row.begin(), row.end(), byColumn))
    std::sort(row.begin(), row.end(), byColumn);
  size_t out = 0;
  for (size_t k = 0; k < row.size();) {
    FormFactorEntry e = row[k++];
    while (k < row.size() && row[k].column == e.column) e.value += row[k++].value;
    row[out++] = e;
  }
  row.resize(out);
}

std::vector<FormFactorEntry> exactPatchRow(const ExactColumns& exact, uint32_t patch) {
  std::vector<FormFactorEntry> row = exact.exactRows[patch];
  row.insert(row.end(), exact.toExact[patch].begin(), exact.toExact[patch].end());
  mergeByColumn(row);
  return row;
}

std::vector<HemisphereHit> hemisphereHits(const PatchMesh& mesh, const RayCaster& caster,
                                          uint32_t patch, int rays, uint64_t seed, uint64_t stream,
                                          const HitKey& keyOf) {
  const int side = strataPerSide(rays);
  const int n = side * side;
  Rng rng(seed, stream);
  const std::vector<int> pointStratum = randomPermutation(n, rng);

  const Patch& p = mesh.patches()[patch];
  const float offset = mesh.rayOffset();
  // Rays leave the covered part only: each origin weighted by its coverage over the mean.
  const bool weighByCoverage = !mesh.uniformCoverage(patch);
  std::vector<Ray> batch(static_cast<size_t>(n));
  std::vector<float> weight(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) {
    const Vec2 up = sampleStratum(pointStratum[k], side, rng);
    const Vec2 ud = sampleStratum(k, side, rng);
    const Vec3 origin = mesh.samplePoint(patch, up, weight[k]);
    if (weighByCoverage)
      weight[k] *= p.coverage > 0.0f ? mesh.coverageAt(patch, origin) / p.coverage : 0.0f;
    batch[k] = {origin + offset * p.normal, toWorld(sampleCosineHemisphere(ud), p.normal)};
  }
  std::vector<Hit> hits(static_cast<size_t>(n));
  caster.intersect(batch, hits);
  std::vector<HemisphereHit> out;
  out.reserve(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) {
    if (!hits[k].valid()) continue;
    const Vec3 at = batch[k].origin + hits[k].distance * batch[k].direction;
    const uint64_t key = keyOf(hits[k].triangle, hits[k].frontFace, at);
    if (key != kNoKey) out.push_back({key, weight[k] / float(n)});
  }
  sortByKey(out);
  return out;
}

std::vector<FormFactorEntry> hemisphereRow(const PatchMesh& mesh, const RayCaster& caster,
                                           uint32_t patch, int rays, uint64_t seed,
                                           const ExactColumns* exact) {
  if (exact && exact->isExact[patch]) return exactPatchRow(*exact, patch);
  // The key of a hit is its patch: the mesh as it is.
  const std::vector<HemisphereHit> hits = hemisphereHits(
      mesh, caster, patch, rays, seed, patch, [&](uint32_t triangle, bool front, const Vec3& at) {
        const uint32_t j = mesh.locate(triangle, front, at).patch;
        return j == kNoPatch ? kNoKey : uint64_t(j);
      });
  return rowFromHits(
      hits, patch, [](uint64_t key) { return uint32_t(key); }, exact);
}

FormFactorRows hemisphereFormFactors(const PatchMesh& mesh, const RayCaster& caster,
                                     const FormFactorSettings& settings,
                                     const ProgressCallback& progress) {
  const std::optional<ExactColumns> exact = exactColumns(mesh, caster, settings);
  FormFactorRows rows(mesh.size());
  ProgressTicker ticker(progress, rows.size());
  tbb::parallel_for(size_t(0), rows.size(), [&](size_t i) {
    if (ticker.cancelled()) return;
    rows[i] = hemisphereRow(mesh, caster, uint32_t(i), settings.rays, settings.seed,
                            exact ? &*exact : nullptr);
    ticker.tick();
  });
  ticker.throwIfCancelled();
  return rows;
}

}  // namespace rad
