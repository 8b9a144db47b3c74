// Area-to-area form factors by Monte Carlo over point pairs: F_ij = (1/A_i) int int
// cos_i cos_j V / (pi r^2) dA_j dA_i, estimated by A_j times the mean of cos_i cos_j V / (pi r^2)
// over uniform point pairs (Cohen and Wallace, "Radiosity and Realistic Image Synthesis" (1993),
// eq. 4.11 and section 4.9). The same mean times A_i gives F_ji, so each pair's geometric terms
// and visibility rays are computed once for both rows (reciprocity holds exactly). Patches that
// touch (a shared edge or corner) make cos cos / (pi r^2) singular and the estimator's variance
// infinite, so for those pairs the inner integral over j is taken exactly instead (Lambert's
// contour formula, docs/references.md 1(f)) at stratified points of i, still with a visibility ray.
#include <tbb/parallel_for.h>

#include <array>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <span>

#include "core/progress_ticker.h"
#include "core/rng.h"
#include "geometry/point_polygon_form_factor.h"
#include "geometry/sampling.h"
#include "patch/form_factor_estimators.h"
#include "patch/row_exchange.h"

namespace rad {

namespace {

// Some corner of each patch lies strictly in front of the other's plane.
bool facing(const PatchMesh& mesh, uint32_t i, uint32_t j) {
  auto inFront = [&](uint32_t a, uint32_t b) {
    std::array<Vec3, 4> c;
    const int n = mesh.corners(b, c);
    const Patch& pa = mesh.patches()[a];
    const float eps = mesh.rayOffset();
    for (int k = 0; k < n; ++k)
      if (glm::dot(c[k] - pa.centroid, pa.normal) > eps) return true;
    return false;
  };
  return inFront(i, j) && inFront(j, i);
}

// Mean of cos cos V / (pi r^2) over `pairs` stratified point pairs of patches i and j.
double pairMean(const PatchMesh& mesh, const RayCaster& caster, uint32_t i, uint32_t j, int pairs,
                Rng& rng) {
  const int side = strataPerSide(pairs);
  const int n = side * side;
  const std::vector<int> perm = randomPermutation(n, rng);
  const Patch &pi = mesh.patches()[i], &pj = mesh.patches()[j];
  const float offset = mesh.rayOffset();
  std::vector<Ray> rays;
  std::vector<double> g;
  rays.reserve(static_cast<size_t>(n));
  g.reserve(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) {
    float wi, wj;
    const Vec3 a = mesh.samplePoint(i, sampleStratum(k, side, rng), wi) + offset * pi.normal;
    const Vec3 b = mesh.samplePoint(j, sampleStratum(perm[k], side, rng), wj) + offset * pj.normal;
    const Vec3 d = b - a;
    const double r2 = glm::dot(d, d);
    const double ci = glm::dot(d, pi.normal), cj = -glm::dot(d, pj.normal);
    if (ci <= 0.0 || cj <= 0.0 || r2 <= 0.0) continue;
    g.push_back(double(wi) * wj * ci * cj / (glm::pi<double>() * r2 * r2));
    rays.push_back({a, d, 0.0f, 1.0f});
  }
  std::vector<uint8_t> blocked(rays.size());
  caster.occluded(rays, blocked);
  double sum = 0.0;
  for (size_t k = 0; k < g.size(); ++k) sum += blocked[k] ? 0.0 : g[k];
  return sum / double(n);
}

// Some corner of one patch lies (almost) on a corner of the other.
bool touching(const PatchMesh& mesh, uint32_t i, uint32_t j) {
  std::array<Vec3, 4> a, b;
  const int na = mesh.corners(i, a), nb = mesh.corners(j, b);
  const float near = 0.01f * std::sqrt(std::min(mesh.patches()[i].area, mesh.patches()[j].area));
  for (int x = 0; x < na; ++x)
    for (int y = 0; y < nb; ++y)
      if (glm::distance(a[x], b[y]) <= near) return true;
  return false;
}

// For touching patches: the mean of F(x -> j) / A_j V over stratified points x of i, which is the
// same quantity pairMean estimates, with the singular inner integral done exactly.
double touchingPairMean(const PatchMesh& mesh, const RayCaster& caster, uint32_t i, uint32_t j,
                        int pairs, Rng& rng) {
  const int side = strataPerSide(pairs);
  std::array<Vec3, 4> c;
  const int n = mesh.corners(j, c);
  std::array<Vec3d, 4> corners;
  for (int k = 0; k < n; ++k) corners[k] = Vec3d(c[k]);
  const std::span<const Vec3d> polygon(corners.data(), size_t(n));
  const Patch &pi = mesh.patches()[i], &pj = mesh.patches()[j];
  const float offset = mesh.rayOffset();
  std::vector<Ray> rays;
  std::vector<double> f;
  for (int k = 0; k < side * side; ++k) {
    float wi, wj;
    const Vec3 x = mesh.samplePoint(i, sampleStratum(k, side, rng), wi);
    f.push_back(double(wi) * pointPolygonFormFactor(Vec3d(x), Vec3d(pi.normal), polygon));
    const Vec3 a = x + offset * pi.normal;
    const Vec3 b = mesh.samplePoint(j, uniformSquare(rng), wj) + offset * pj.normal;
    rays.push_back({a, b - a, 0.0f, 1.0f});
  }
  std::vector<uint8_t> blocked(rays.size());
  caster.occluded(rays, blocked);
  double sum = 0.0;
  for (size_t k = 0; k < f.size(); ++k) sum += blocked[k] ? 0.0 : f[k];
  return sum / double(f.size()) / std::max(double(pj.area), 1e-300);
}

}  // namespace

FormFactorRows pairwiseFormFactors(const PatchMesh& mesh, const RayCaster& caster,
                                   const FormFactorSettings& settings,
                                   const ProgressCallback& progress) {
  const size_t n = mesh.size();
  struct PairValue {
    uint32_t j;
    double mean;
  };
  std::vector<std::vector<PairValue>> upper(n);
  // Split among processes: each every count-th row (row i has n - i - 1 pairs: blocks would
  // leave the first rank the most), then every row to every process.
  const std::vector<uint32_t> mine = rowsOf(settings.processes, RowShare::Interleaved, n);
  ProgressTicker ticker(progress, mine.size());
  tbb::parallel_for(size_t(0), mine.size(), [&](size_t k) {
    if (ticker.cancelled()) return;
    const size_t i = mine[k];
    Rng rng(settings.seed, i);
    for (uint32_t j = uint32_t(i) + 1; j < n; ++j) {
      if (!facing(mesh, uint32_t(i), j)) continue;
      const double mean = touching(mesh, uint32_t(i), j)
                              ? touchingPairMean(mesh, caster, uint32_t(i), j, settings.rays, rng)
                              : pairMean(mesh, caster, uint32_t(i), j, settings.rays, rng);
      if (mean > 0.0) upper[i].push_back({j, mean});
    }
    ticker.tick();
  });
  ticker.throwIfCancelled();
  if (settings.processes.split()) exchangeRows(settings.processes, RowShare::Interleaved, upper);
  // Row r gets its columns i < r (in increasing i) before its own j > r: sorted, as fromRows
  // takes them.
  FormFactorRows rows(n);
  const auto& patches = mesh.patches();
  for (uint32_t i = 0; i < n; ++i)
    for (const PairValue& pv : upper[i]) {
      rows[i].push_back({pv.j, float(pv.mean * patches[pv.j].coveredArea())});
      rows[pv.j].push_back({i, float(pv.mean * patches[i].coveredArea())});
    }
  return rows;
}

}  // namespace rad
