// One pass of the lights' direct light over every patch, for `radiosity bench patch`
// (radiosity/kernel_timing.h): the first shot's cost, and what relighting pays a frame.
#include <radiosity/kernel_timing.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>

#include "lighting/direct_lighting.h"
#include "patch/patch_light_injection.h"
#include "patch/patch_mesh.h"

namespace rad {

DirectLightPassTiming measurePatchDirectLight(const Scene& scene, size_t patches,
                                              int pointsPerPatch) {
  const PatchMesh mesh(scene, {0.0f, patches});
  const RayCaster caster(scene);
  const DirectLighting direct(scene, caster);
  std::vector<Color> d(mesh.size());
  constexpr int kPasses = 21;
  std::vector<double> ms;
  for (int pass = 0; pass < kPasses; ++pass) {
    const auto start = std::chrono::steady_clock::now();
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, uint32_t(mesh.size()), 64),
                      [&](const auto& r) {
                        for (uint32_t p = r.begin(); p != r.end(); ++p)
                          d[p] = lightOnPatch(mesh, p, direct, pointsPerPatch).direct;
                      });
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                     .count());
  }
  std::nth_element(ms.begin(), ms.begin() + kPasses / 2, ms.end());
  return {mesh.size(), ms[kPasses / 2]};
}

}  // namespace rad
