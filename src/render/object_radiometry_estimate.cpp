// estimateObjectRadiometry: per-object mean irradiance and radiosity by Monte Carlo, the
// reference for the radiosity methods' per-surface results. Points are stratified along each
// object's cumulative triangle area (so their plain mean is the area-weighted mean); each point
// has its own random stream, so the result does not depend on the thread count.
#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/path_tracer.h>
#include <radiosity/process_memory.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <glm/gtc/constants.hpp>

#include "core/process_collectives.h"
#include "core/progress_ticker.h"
#include "geometry/sampling.h"
#include "render/path_integrator.h"
#include "render/path_tracer_settings.h"

namespace rad {

namespace {

// An object's front-facing triangles and their cumulative areas.
struct ObjectSurface {
  std::vector<uint32_t> triangles;
  std::vector<double> cumulativeArea;
  double area() const { return cumulativeArea.empty() ? 0.0 : cumulativeArea.back(); }
};

std::vector<ObjectSurface> objectSurfaces(const Scene& scene) {
  std::vector<ObjectSurface> surfaces(scene.objects.size());
  for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
    const uint32_t object = scene.faceOf(t).object;
    if (object >= surfaces.size()) continue;
    ObjectSurface& s = surfaces[object];
    s.triangles.push_back(t);
    s.cumulativeArea.push_back(s.area() + double(scene.triangleArea(t)));
  }
  return surfaces;
}

struct SurfacePoint {
  Vec3 position;
  uint32_t triangle;
  Vec2 barycentric;
};

// Point k of n: the k-th stratum of the cumulative area, jittered.
SurfacePoint stratifiedPoint(const Scene& scene, const ObjectSurface& s, int k, int n, Rng& rng) {
  const double target = (double(k) + double(rng.uniform())) / double(n) * s.area();
  const auto it = std::upper_bound(s.cumulativeArea.begin(), s.cumulativeArea.end(), target);
  const size_t i = std::min(size_t(it - s.cumulativeArea.begin()), s.triangles.size() - 1);
  const double before = i == 0 ? 0.0 : s.cumulativeArea[i - 1];
  const double within = (target - before) / (s.cumulativeArea[i] - before);
  const Vec2 b = sampleUniformTriangle(Vec2(std::clamp(float(within), 0.0f, 1.0f), rng.uniform()));
  const uint32_t t = s.triangles[i];
  const UVec3& tri = scene.triangles[t];
  return {(1.0f - b.x - b.y) * scene.positions[tri.x] + b.x * scene.positions[tri.y] +
              b.y * scene.positions[tri.z],
          t, b};
}

}  // namespace

std::vector<ObjectRadiometry> estimateObjectRadiometry(const Scene& scene, int pointsPerObject,
                                                       const PathTracerSettings& settings,
                                                       PathTracerStats* stats,
                                                       const ProgressCallback& progress) {
  validatePathTracerSettings(settings);
  return estimateObjectRadiometry(scene, RayCaster(scene), pointsPerObject, settings, stats,
                                  progress);
}

std::vector<ObjectRadiometry> estimateObjectRadiometry(const Scene& scene, const RayCaster& caster,
                                                       int pointsPerObject,
                                                       const PathTracerSettings& settings,
                                                       PathTracerStats* stats,
                                                       const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  validatePathTracerSettings(settings);
  if (pointsPerObject < 1)
    throw InputError("path tracer",
                     fmt::format("points per object {} out of range [1, inf)", pointsPerObject));
  const uint64_t raysBefore = caster.raysCast();
  const PathIntegrator integrator(scene, caster, settings.maxDepth);
  const std::vector<ObjectSurface> surfaces = objectSurfaces(scene);

  const size_t n = size_t(pointsPerObject);
  const size_t totalPoints = surfaces.size() * n;
  requireMemory(double(totalPoints) * 2.0 * sizeof(Color), "object points",
                fmt::format("{} points on each of {} objects", n, surfaces.size()),
                "use fewer points per object");
  std::vector<Color> irradiance(totalPoints, Color(0.0f)), radiosity(totalPoints, Color(0.0f));
  // Split among processes: every count-th point a process, the points' values added up after
  // (each point is one process's, the others' zeros: exact).
  const ProcessShare& share = settings.processes;
  ProgressTicker ticker(progress, totalPoints / size_t(share.count));
  tbb::parallel_for(tbb::blocked_range<size_t>(0, totalPoints), [&](const auto& range) {
    for (size_t index = range.begin(); index != range.end(); ++index) {
      if (ticker.cancelled()) return;
      if (index % size_t(share.count) != size_t(share.rank)) continue;
      const ObjectSurface& s = surfaces[index / n];
      if (s.triangles.empty()) continue;
      Rng rng(settings.seed, uint64_t(index));
      const SurfacePoint point = stratifiedPoint(scene, s, int(index % n), int(n), rng);
      const Vec3 normal = scene.triangleNormal(point.triangle);
      Color sum(0.0f);
      for (int k = 0; k < settings.samplesPerPixel; ++k)
        sum += integrator.irradiance(point.position, normal, rng);
      irradiance[index] = sum / float(settings.samplesPerPixel);
      radiosity[index] = glm::pi<float>() * scene.emissionAt(point.triangle, point.barycentric) +
                         scene.reflectanceAt(point.triangle, point.barycentric) * irradiance[index];
      ticker.tick();
    }
  });
  ticker.throwIfCancelled();
  sumOverProcesses(share, irradiance);
  sumOverProcesses(share, radiosity);

  std::vector<ObjectRadiometry> result(surfaces.size());
  for (size_t o = 0; o < surfaces.size(); ++o) {
    result[o].name = scene.objects[o].name;
    result[o].area = surfaces[o].area();
    if (surfaces[o].triangles.empty()) continue;
    Vec3d h(0.0), b(0.0);
    for (size_t k = 0; k < n; ++k) {
      h += Vec3d(irradiance[o * n + k]);
      b += Vec3d(radiosity[o * n + k]);
    }
    result[o].meanIrradiance = Color(h / double(n));
    result[o].meanRadiosity = Color(b / double(n));
  }
  if (stats) {
    stats->rays = sumOverProcesses(share, caster.raysCast() - raysBefore);
    stats->paths = uint64_t(totalPoints) * uint64_t(settings.samplesPerPixel);
    stats->seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return result;
}

}  // namespace rad
