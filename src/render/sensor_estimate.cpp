// estimateSensorIrradiance: the path tracer's irradiance at sensor points, the reference the
// radiosity methods' sensors (sensor_gather.cpp) are judged against. Each point has its own
// random stream, so the result does not depend on the thread count; the points are split among
// processes as the per-object estimate splits its points.
#include <radiosity/error.h>
#include <radiosity/path_tracer.h>
#include <radiosity/sensors.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <glm/geometric.hpp>

#include "core/process_collectives.h"
#include "core/progress_ticker.h"
#include "render/path_integrator.h"
#include "render/path_tracer_settings.h"

namespace rad {

std::vector<Color> estimateSensorIrradiance(const Scene& scene, const RayCaster& caster,
                                            std::span<const SensorPoint> points,
                                            const SensorSettings& sensors,
                                            const PathTracerSettings& settings,
                                            PathTracerStats* stats,
                                            const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  validatePathTracerSettings(settings);
  validateSensorSettings(sensors, "sensors");
  const uint64_t raysBefore = caster.raysCast();
  const PathIntegrator integrator(scene, caster, settings.maxDepth);
  std::vector<Color> irradiance(points.size(), Color(0.0f));
  const ProcessShare& share = settings.processes;
  ProgressTicker ticker(progress, points.size() / size_t(share.count));
  tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size()), [&](const auto& range) {
    for (size_t i = range.begin(); i != range.end(); ++i) {
      if (ticker.cancelled()) return;
      if (i % size_t(share.count) != size_t(share.rank)) continue;
      Rng rng(sensors.seed, uint64_t(i));
      const Vec3 n = glm::normalize(points[i].normal);
      Color sum(0.0f);
      for (int k = 0; k < sensors.hemisphereRays; ++k)
        sum += integrator.irradiance(points[i].position, n, rng);
      irradiance[i] = sum / float(sensors.hemisphereRays);
      ticker.tick();
    }
  });
  ticker.throwIfCancelled();
  sumOverProcesses(share, irradiance);
  if (stats) {
    stats->rays = sumOverProcesses(share, caster.raysCast() - raysBefore);
    stats->paths = uint64_t(points.size()) * uint64_t(sensors.hemisphereRays);
    stats->seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return irradiance;
}

}  // namespace rad
