// Relighting at frame rate: a spot swinging through a furnished room (room:4 with a spot added
// under the ceiling's centre, swung +-35 degrees about the z axis, 4 s a period at 60 frames per
// second), relit frame after frame. The first period casts the master table's rows of every
// node the beam edge refines (the first time); the next half period (one swing across) is
// measured: ms per relight (median, 90th percentile and worst), its parts, the patches brought
// up to date per frame, the master table's hit rate, and the worst error against fresh solves of
// the same lights (every 24th frame; model and fresh solves at tolerance 1e-5, so the reference
// is converged).
#include <fmt/format.h>
#include <radiosity/relighter.h>
#include <radiosity/scene_loader.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <glm/gtc/constants.hpp>

#include "bench_workloads.h"

namespace rad::cli {

namespace {

constexpr int kFramesPerPeriod = 240;
constexpr float kSwingDeg = 35.0f;

Scene roomWithSpot() {
  Scene scene = loadScene("room:4");
  const Bounds b = scene.bounds();
  Light spot;
  spot.type = LightType::Spot;
  spot.position = Vec3(0.5f * (b.min.x + b.max.x), b.max.y - 0.15f, 0.5f * (b.min.z + b.max.z));
  spot.intensity = Color(60.0f, 55.0f, 45.0f);
  spot.innerAngleDeg = 15.0f;
  spot.outerAngleDeg = 25.0f;
  scene.lights.push_back(spot);
  return scene;
}

// A light scenario: the lights at frame f.
using LightsAt = std::function<std::vector<Light>(int frame)>;

float swing(int frame) {
  return std::sin(2.0f * glm::pi<float>() * float(frame) / float(kFramesPerPeriod));
}

std::vector<Light> swung(const Scene& scene, int frame) {
  std::vector<Light> lights = scene.lights;
  const float a = glm::radians(kSwingDeg) * swing(frame);
  lights.back().direction = Vec3(std::sin(a), -std::cos(a), 0.0f);
  return lights;
}

std::vector<Light> dimmed(const Scene& scene, int frame) {
  std::vector<Light> lights = scene.lights;
  lights.back().intensity *= 0.55f + 0.45f * swing(frame);
  return lights;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const size_t k = std::min(v.size() - 1, size_t(q * double(v.size())));
  std::nth_element(v.begin(), v.begin() + long(k), v.end());
  return v[k];
}

// Frames of warm-up (0: a period) and measured (0: half a period).
struct FrameCounts {
  int warmUp = kFramesPerPeriod, measured = kFramesPerPeriod / 2;
};

nlohmann::json measure(const char* name, const Scene& scene, const PatchRadiositySettings& s,
                       const LightsAt& lightsAt, const FrameCounts& frames, Console& console,
                       const RelightSettings& relight = {}) {
  const PatchModel model(scene, s);
  console.detail(fmt::format("bench relight: {}, ~{} patches", name, s.targetPatches));
  const auto start = std::chrono::steady_clock::now();
  Relighter relighter(model, lightsAt(0), relight);
  const double startSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  size_t firstPeriodRows = 0;
  for (int f = 1; f <= frames.warmUp; ++f)
    firstPeriodRows += relighter.relight(lightsAt(f)).rowsComputed;
  std::vector<double> ms, directMs, formFactorMs, bounceMs;
  double updated = 0.0, worstError = 0.0;
  size_t rowsComputed = 0, rowsReused = 0, meshChanges = 0, fresh = 0;
  // By default half a period: the swing from one side to the other.
  const int last = frames.warmUp + frames.measured;
  for (int f = frames.warmUp + 1; f <= last; ++f) {
    const std::vector<Light> lights = lightsAt(f);
    const RelightStats& r = relighter.relight(lights);
    ms.push_back(r.milliseconds);
    directMs.push_back(r.directMs);
    formFactorMs.push_back(r.formFactorMs);
    bounceMs.push_back(r.bounceMs);
    updated += double(r.patchesUpdated) / double(r.patches);
    rowsComputed += r.rowsComputed;
    rowsReused += r.rowsReused;
    meshChanges += r.meshChanged;
    if (f % 24 == 0 || (f == last && fresh == 0)) {
      worstError = std::max(worstError,
                            largestRadiosityDifference(relighter.solution(), model.solve(lights)));
      ++fresh;
    }
  }
  const double measured = double(ms.size());
  const size_t rows = rowsComputed + rowsReused;
  nlohmann::json result = {{"scenario", name},
                           {"patches", relighter.solution().elementCount()},
                           {"frames", ms.size()},
                           {"ms_per_relight", percentile(ms, 0.5)},
                           {"ms_per_relight_p90", percentile(ms, 0.9)},
                           {"ms_per_relight_max", *std::max_element(ms.begin(), ms.end())},
                           {"direct_ms", percentile(directMs, 0.5)},
                           {"form_factors_ms", percentile(formFactorMs, 0.5)},
                           {"bounce_ms", percentile(bounceMs, 0.5)},
                           {"updated_fraction", updated / measured},
                           {"mesh_change_fraction", double(meshChanges) / measured},
                           {"rows_hit_rate", rows > 0 ? double(rowsReused) / double(rows) : 1.0},
                           {"first_period_rows_computed", firstPeriodRows},
                           {"fresh_solves_compared", fresh},
                           {"start_seconds", startSeconds},
                           {"max_rel_error_vs_fresh", worstError}};
  result["summary"] = fmt::format(
      "{}: {} patches, {:.1f} ms per relight (median; p90 {:.1f}; direct {:.1f}, form factors "
      "{:.1f}, bounce {:.1f}), {:.1f}% of patches updated a frame, quadtree changed in {:.0f}% "
      "of frames, master rows hit {:.1f}%, worst error vs fresh {:.3f}%",
      name, result["patches"].get<size_t>(), result["ms_per_relight"].get<double>(),
      result["ms_per_relight_p90"].get<double>(), result["direct_ms"].get<double>(),
      result["form_factors_ms"].get<double>(), result["bounce_ms"].get<double>(),
      100.0 * updated / measured, 100.0 * double(meshChanges) / measured,
      100.0 * result["rows_hit_rate"].get<double>(), 100.0 * worstError);
  return result;
}

}  // namespace

// The swinging spot with the quadtree following its beam (the default settings) comes first
// and gives the top-level numbers; then the same with adaptive subdivision off (a fixed mesh),
// a dimmer on the spot, and on a small fixed mesh delta shooting against the precomputed
// transfer.
nlohmann::json benchRelight(Console& console, size_t patches, int frameCount) {
  const FrameCounts frames = frameCount > 0 ? FrameCounts{frameCount, frameCount} : FrameCounts{};
  const Scene scene = roomWithSpot();
  PatchRadiositySettings s;
  s.targetPatches = patches;
  s.tolerance = 1e-5;
  PatchRadiositySettings fixedMesh = s;
  fixedMesh.refineLevels = 0;
  const LightsAt swinging = [&](int f) { return swung(scene, f); };
  nlohmann::json scenarios = nlohmann::json::array(
      {measure("swinging spot", scene, s, swinging, frames, console),
       measure("swinging spot, fixed mesh", scene, fixedMesh, swinging, frames, console),
       measure(
           "dimmed spot", scene, s, [&](int f) { return dimmed(scene, f); }, frames, console)});
  PatchRadiositySettings small = fixedMesh;
  small.targetPatches = std::min<size_t>(patches, 1500);
  RelightSettings shooting, transfer;
  shooting.transferPatches = 0;
  transfer.transferPatches = 4000;
  scenarios.push_back(measure("small fixed mesh, delta shooting", scene, small, swinging, frames,
                              console, shooting));
  scenarios.push_back(measure("small fixed mesh, precomputed transfer", scene, small, swinging,
                              frames, console, transfer));
  nlohmann::json result = scenarios[0];
  std::string summary;
  for (const auto& r : scenarios)
    summary += (summary.empty() ? "" : "; ") + r["summary"].get<std::string>();
  result["scenarios"] = scenarios;
  result["summary"] = summary;
  return result;
}

}  // namespace rad::cli
