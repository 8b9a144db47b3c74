#pragma once
// Deterministic quadrature over a patch: where the exact form factors and the direct light from
// analytic lights are evaluated, so that a beam or shadow edge crossing a patch gives it the
// share of light that falls on it.

#include <cstdint>
#include <vector>

#include "patch/patch_mesh.h"

namespace rad {

struct QuadraturePoint {
  Vec3 position;
  double weight;  ///< the weights sum to 1 over the patch
};

/// The composite midpoint rule with at least `points` points (a square number of cells): a
/// quad's parameter square in side x side cells (weighted by the bilinear map's area density), a
/// triangle in side^2 congruent sub-triangles (at their centroids). Both are second-order
/// accurate for smooth integrands.
std::vector<QuadraturePoint> midpointRule(const PatchMesh& mesh, uint32_t patch, int points);

/// The same with each weight times the coverage at its point, and the weights scaled to sum to
/// 1 again: the mean over the patch's covered part (Patch::coverage). The plain rule where the
/// coverage is uniform or the points find none.
std::vector<QuadraturePoint> coveredMidpointRule(const PatchMesh& mesh, uint32_t patch, int points);

}  // namespace rad
