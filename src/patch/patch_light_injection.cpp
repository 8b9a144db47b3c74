#include "patch/patch_light_injection.h"

#include <array>

#include "patch/patch_quadrature.h"

namespace rad {

PatchLight lightOnPatch(const PatchMesh& mesh, uint32_t patch, const DirectLighting& direct,
                        int points) {
  const Patch& p = mesh.patches()[patch];
  std::vector<QuadraturePoint> at = midpointRule(mesh, patch, points);
  const size_t quadrature = at.size();
  std::array<Vec3, 4> corners;
  const int n = mesh.corners(patch, corners);
  for (int k = 0; k < n; ++k) at.push_back({corners[k] + 0.02f * (p.centroid - corners[k]), 0.0});
  PatchLight out;
  Vec3d sum(0.0);
  for (const Light& light : direct.lights()) {
    bool lit = false, dark = false;
    for (size_t i = 0; i < at.size(); ++i) {
      const Color e = direct.fromLight(light, at[i].position, p.normal);
      (maxComponent(e) > 0.0f ? lit : dark) = true;
      if (i < quadrature) sum += at[i].weight * Vec3d(e);
    }
    out.edgeInside = out.edgeInside || (lit && dark);
  }
  out.direct = Color(sum);
  return out;
}

}  // namespace rad
