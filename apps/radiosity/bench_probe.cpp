// Probes for objects that move: a cube view of the Cornell box's patch solution captured at the
// box's centre, then the irradiance of a 10k-vertex object's vertices (the normals of a sphere)
// by each of the three ways. ms a capture and ms a frame per object (capture plus its vertices).
#include <fmt/format.h>
#include <radiosity/kernel_timing.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/placed_objects.h>
#include <radiosity/scene_loader.h>

#include <cmath>
#include <glm/gtc/constants.hpp>

#include "bench_workloads.h"

namespace rad::cli {

namespace {

// `count` unit normals spread over the sphere (a Fibonacci lattice).
std::vector<Vec3> sphereNormals(size_t count) {
  std::vector<Vec3> normals(count);
  const double golden = glm::pi<double>() * (3.0 - std::sqrt(5.0));
  for (size_t k = 0; k < count; ++k) {
    const double z = 1.0 - 2.0 * (double(k) + 0.5) / double(count);
    const double r = std::sqrt(1.0 - z * z), phi = golden * double(k);
    normals[k] = Vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
  }
  return normals;
}

}  // namespace

nlohmann::json benchProbe(Console& console, int resolution) {
  const Scene scene = loadScene("cornell");
  const RayCaster caster(scene);
  PatchRadiositySettings settings;
  settings.cacheDir.clear();
  const PatchRadiosity solution = PatchModel(scene, caster, settings).solve(scene.lights);
  const Bounds b = scene.bounds();
  const Vec3 centre = 0.5f * (b.min + b.max);
  console.detail(fmt::format("bench probe: {0}x{0} texels a face", resolution));
  const std::vector<Vec3> normals = sphereNormals(10000);
  const CubeProbeTiming timing = measureCubeProbe(caster, solution, centre, resolution, normals);
  const double captureMs = timing.captureMs;
  nlohmann::json ways = nlohmann::json::object();
  std::string summary = fmt::format("probe {0}x{0}: capture {1:.2f} ms", resolution, captureMs);
  for (const auto& [name, way] : {std::pair{"exact", ProbeIrradiance::Exact},
                                  std::pair{"harmonic", ProbeIrradiance::Harmonic},
                                  std::pair{"pattern", ProbeIrradiance::Pattern}}) {
    const double ms = timing.irradianceMs[int(way)];
    ways[name] = {{"vertices_ms", ms}, {"frame_ms", captureMs + ms}};
    summary += fmt::format("; {} {:.2f} ms for 10k vertices ({:.2f} ms a frame)", name, ms,
                           captureMs + ms);
  }
  return {{"resolution", resolution},
          {"vertices", normals.size()},
          {"capture_ms", captureMs},
          {"ways", ways},
          {"summary", summary}};
}

}  // namespace rad::cli
