#include "patch/patch_light_injection.h"

#include <tbb/parallel_for.h>

#include "patch/patch_quadrature.h"
#include "render/progress_ticker.h"

namespace rad {

std::vector<Color> patchLightIrradiance(const PatchMesh& mesh, const DirectLighting& direct,
                                        int points, const ProgressCallback& progress) {
  if (!direct.hasLights()) return {};
  std::vector<Color> irradiance(mesh.size());
  ProgressTicker ticker(progress, mesh.size());
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, uint32_t(mesh.size()), 64), [&](const auto& r) {
    for (uint32_t p = r.begin(); p != r.end() && !ticker.cancelled(); ++p) {
      const Vec3& n = mesh.patches()[p].normal;
      Vec3d sum(0.0);
      for (const QuadraturePoint& q : midpointRule(mesh, p, points))
        sum += q.weight * Vec3d(direct.fromLights(q.position, n));
      irradiance[p] = Color(sum);
      ticker.tick();
    }
  });
  ticker.throwIfCancelled();
  return irradiance;
}

}  // namespace rad
