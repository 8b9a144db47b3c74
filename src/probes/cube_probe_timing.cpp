// A cube probe's cost, for `radiosity bench probe` (radiosity/kernel_timing.h): its capture and
// the irradiance of many vertices from it by each way.
#include <radiosity/kernel_timing.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <functional>

#include "probes/cube_probe.h"

namespace rad {

namespace {

double meanMs(const std::function<void()>& work, int repeats) {
  const auto start = std::chrono::steady_clock::now();
  for (int r = 0; r < repeats; ++r) work();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
             .count() /
         repeats;
}

}  // namespace

CubeProbeTiming measureCubeProbe(const RayCaster& caster, const SurfaceRadiance& radiance,
                                 const Vec3& centre, int resolution,
                                 std::span<const Vec3> normals) {
  CubeProbe probe(resolution);
  CubeProbeTiming timing;
  timing.captureMs = meanMs([&] { probe.capture(caster, radiance, centre); }, 20);
  std::vector<Color> irradiance(normals.size());
  for (ProbeIrradiance way :
       {ProbeIrradiance::Exact, ProbeIrradiance::Harmonic, ProbeIrradiance::Pattern}) {
    const int repeats = way == ProbeIrradiance::Exact ? 2 : 20;
    timing.irradianceMs[int(way)] = meanMs(
        [&] {
          tbb::parallel_for(size_t(0), normals.size(),
                            [&](size_t v) { irradiance[v] = probe.irradiance(normals[v], way); });
        },
        repeats);
  }
  return timing;
}

}  // namespace rad
