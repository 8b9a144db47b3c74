// Form factors from the exact point-to-polygon factor (Lambert's contour integral,
// docs/references.md 1(f)) integrated over patch i by the midpoint rule on its parameter square,
// each point's factor scaled by the visibility of patch j along one jittered ray (the "ray-traced
// form factor" of Wallace, Elmquist and Haines, SIGGRAPH 1989, with the analytic kernel of Cohen
// and Wallace, "Radiosity and Realistic Image Synthesis" (1993), eq. 3.53).
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <optional>

#include "core/progress_ticker.h"
#include "core/rng.h"
#include "geometry/point_polygon_form_factor.h"
#include "geometry/sampling.h"
#include "patch/form_factor_estimators.h"
#include "patch/patch_quadrature.h"
#include "patch/row_exchange.h"

namespace rad {

namespace {

// The exact estimator's pair computation for the rows of any set of columns.
class ExactKernel {
 public:
  ExactKernel(const PatchMesh& mesh, const RayCaster& caster)
      : mesh_(mesh), caster_(caster), polygons_(mesh.size()), offset_(mesh.rayOffset()) {
    for (uint32_t j = 0; j < mesh.size(); ++j) {
      std::array<Vec3, 4> c;
      const int k = mesh.corners(j, c);
      for (int m = 0; m < k; ++m) polygons_[j].push_back(Vec3d(c[m]));
    }
  }

  /// (j, F_ij) for each patch j != i of `columns` (ascending) with F_ij > 0. Each pair is
  /// integrated over the smaller of its two patches, toward the other's polygon (exact), and
  /// F_ij follows by reciprocity where that is j: the kernel peaks within a patch's size of the
  /// other, and a few points on a patch far larger than its distance to a small one miss or hit
  /// the peak (an 80 m floor one patch under a lamp 1 m above it got 1.4% of the lamp's light;
  /// a real atrium's lamps, row sums up to 325).
  template <class Columns>
  std::vector<FormFactorEntry> row(uint32_t i, int points, Rng& rng, const Columns& columns) const {
    const std::vector<QuadraturePoint> own = coveredMidpointRule(mesh_, i, points);
    std::vector<QuadraturePoint> other;
    std::vector<FormFactorEntry> entries;
    for (const uint32_t j : columns) {
      if (j == i) continue;
      const bool fromJ = mesh_.patches()[j].area < mesh_.patches()[i].area;
      if (fromJ) other = coveredMidpointRule(mesh_, j, points);
      const double f = pairFactor(fromJ ? j : i, fromJ ? i : j, fromJ ? other : own, rng);
      const double fij =
          fromJ ? f * mesh_.patches()[j].coveredArea() / mesh_.patches()[i].coveredArea() : f;
      if (fij > 0.0) entries.push_back({j, float(fij)});
    }
    return entries;
  }

 private:
  // F_ab: the point-to-polygon factor toward b at the points `q` of a, each times the
  // visibility of b along one ray to a random point of it, times b's mean coverage (the kernel
  // sees b's whole polygon; a cut-out's holes are taken as spread evenly over it).
  double pairFactor(uint32_t a, uint32_t b, const std::vector<QuadraturePoint>& q, Rng& rng) const {
    const Patch& pa = mesh_.patches()[a];
    std::vector<double> f(q.size());
    // The kernel first: it is 0 wherever b does not face the point, and then no ray is needed.
    double any = 0.0;
    for (size_t k = 0; k < q.size(); ++k) {
      f[k] = pointPolygonFormFactor(Vec3d(q[k].position), Vec3d(pa.normal), polygons_[b]);
      any += f[k];
    }
    if (any <= 0.0) {
      // Skip the targets' random numbers all the same, so that each pair keeps its targets.
      for (size_t k = 0; k < 2 * q.size(); ++k) rng.next();
      return 0.0;
    }
    const Patch& pb = mesh_.patches()[b];
    std::vector<Ray> rays(q.size());
    std::vector<uint8_t> blocked(q.size());
    for (size_t k = 0; k < q.size(); ++k) {
      float w;
      const Vec3 target = mesh_.samplePoint(b, uniformSquare(rng), w) + offset_ * pb.normal;
      const Vec3 origin = q[k].position + offset_ * pa.normal;
      rays[k] = {origin, target - origin, 0.0f, 1.0f};
    }
    caster_.occluded(rays, blocked);
    double sum = 0.0;
    for (size_t k = 0; k < q.size(); ++k) sum += blocked[k] ? 0.0 : q[k].weight * f[k];
    return sum * pb.coverage;
  }

  const PatchMesh& mesh_;
  const RayCaster& caster_;
  std::vector<std::vector<Vec3d>> polygons_;
  float offset_;
};

}  // namespace

FormFactorRows exactFormFactors(const PatchMesh& mesh, const RayCaster& caster,
                                const FormFactorSettings& settings,
                                const ProgressCallback& progress) {
  const ExactKernel kernel(mesh, caster);
  std::vector<uint32_t> all(mesh.size());
  std::iota(all.begin(), all.end(), 0u);
  FormFactorRows rows(mesh.size());
  // Split among processes: each every count-th row (a row's cost follows what its patch sees,
  // which varies along the table), then every row to every process.
  const std::vector<uint32_t> mine = rowsOf(settings.processes, RowShare::Interleaved, rows.size());
  ProgressTicker ticker(progress, mine.size());
  tbb::parallel_for(size_t(0), mine.size(), [&](size_t k) {
    if (ticker.cancelled()) return;
    const uint32_t i = mine[k];
    Rng rng(settings.seed, i);
    rows[i] = kernel.row(i, settings.rays, rng, all);
    ticker.tick();
  });
  ticker.throwIfCancelled();
  if (settings.processes.split()) exchangeRows(settings.processes, RowShare::Interleaved, rows);
  return rows;
}

std::optional<ExactColumns> exactColumns(const PatchMesh& mesh, const RayCaster& caster,
                                         const FormFactorSettings& settings,
                                         const ExactRowStore* store,
                                         std::span<const uint8_t> wanted) {
  const std::vector<uint32_t>& columns = settings.exactColumns;
  if (columns.empty()) return std::nullopt;
  ExactColumns exact;
  exact.isExact.assign(mesh.size(), 0);
  for (const uint32_t j : columns) exact.isExact[j] = 1;
  exact.toExact.resize(mesh.size());
  std::vector<uint8_t> missing(wanted.begin(), wanted.end());
  if (wanted.empty()) missing.assign(mesh.size(), 1);
  if (store)
    tbb::parallel_for(size_t(0), mesh.size(), [&](size_t i) {
      if (!missing[i]) return;
      if (auto row = store->known(uint32_t(i))) {
        exact.toExact[i] = std::move(*row);
        missing[i] = 0;
      }
    });
  if (std::find(missing.begin(), missing.end(), 1) != missing.end()) {
    const ExactKernel kernel(mesh, caster);
    // Split among processes as exactFormFactors does (all hold the known rows already).
    const std::vector<uint32_t> mine =
        rowsOf(settings.processes, RowShare::Interleaved, mesh.size());
    tbb::parallel_for(size_t(0), mine.size(), [&](size_t k) {
      const uint32_t i = mine[k];
      if (!missing[i]) return;
      // A stream of its own, apart from the hemisphere rays' (seed, i).
      Rng rng(settings.seed ^ 0x6578616374636f6cull, store ? store->streamOf(uint32_t(i)) : i);
      exact.toExact[i] = kernel.row(uint32_t(i), kExactColumnPoints, rng, columns);
    });
    if (settings.processes.split())
      exchangeRows(settings.processes, RowShare::Interleaved, exact.toExact);
    if (store)
      for (uint32_t i = 0; i < mesh.size(); ++i)
        if (missing[i]) store->computed(i, exact.toExact[i]);
  }
  // The exact patches' rows by reciprocity, in ascending column order (i ascends).
  exact.exactRows.resize(mesh.size());
  if (!wanted.empty()) return exact;
  const std::vector<Patch>& patches = mesh.patches();
  for (uint32_t i = 0; i < mesh.size(); ++i)
    for (const FormFactorEntry& e : exact.toExact[i])
      if (!exact.isExact[i] && patches[e.column].area > 0.0f)
        exact.exactRows[e.column].push_back(
            {i, e.value * patches[i].coveredArea() / patches[e.column].coveredArea()});
  return exact;
}

}  // namespace rad
