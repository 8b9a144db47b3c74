#include "patch/patch_quadrature.h"

#include <array>

#include "geometry/sampling.h"

namespace rad {

std::vector<QuadraturePoint> midpointRule(const PatchMesh& mesh, uint32_t patch, int points) {
  const int side = strataPerSide(points);
  std::vector<QuadraturePoint> q;
  std::array<Vec3, 4> c;
  if (mesh.corners(patch, c) == 3) {
    auto at = [&](double a, double b) {
      return Vec3((1.0 - a - b) * Vec3d(c[0]) + a * Vec3d(c[1]) + b * Vec3d(c[2]));
    };
    const double w = 1.0 / (double(side) * side);
    for (int i = 0; i < side; ++i)
      for (int j = 0; i + j < side; ++j) {
        q.push_back({at((i + 1.0 / 3.0) / side, (j + 1.0 / 3.0) / side), w});
        if (i + j + 1 < side) q.push_back({at((i + 2.0 / 3.0) / side, (j + 2.0 / 3.0) / side), w});
      }
    return q;
  }
  double total = 0.0;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      float w;
      const Vec2 u((float(x) + 0.5f) / float(side), (float(y) + 0.5f) / float(side));
      const Vec3 p = mesh.samplePoint(patch, u, w);
      q.push_back({p, double(w)});
      total += double(w);
    }
  for (QuadraturePoint& p : q) p.weight /= total;
  return q;
}

std::vector<QuadraturePoint> coveredMidpointRule(const PatchMesh& mesh, uint32_t patch,
                                                 int points) {
  std::vector<QuadraturePoint> q = midpointRule(mesh, patch, points);
  if (mesh.uniformCoverage(patch)) return q;
  std::vector<double> weights;
  double total = 0.0;
  for (const QuadraturePoint& p : q) {
    weights.push_back(p.weight * mesh.coverageAt(patch, p.position));
    total += weights.back();
  }
  if (!(total > 0.0)) return q;
  for (size_t k = 0; k < q.size(); ++k) q[k].weight = weights[k] / total;
  return q;
}

}  // namespace rad
