#include <fmt/format.h>
#include <radiosity/atomic_file.h>
#include <radiosity/error.h>
#include <radiosity/kernel_timing.h>
#include <radiosity/scene.h>
#include <radiosity/scene_loader.h>
#include <radiosity/voxel_radiosity.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

#include "bench_workloads.h"
#include "log_log_plot.h"

namespace rad::cli {

namespace {

// The paper's run: 2 million voxels, R = 38 (14,790 directions), 6 iterations, 27 hours on a
// 900 MHz Athlon (Chatelier and Malgouyres 2006).
constexpr double kPaperVisits = 2e6 * 14790.0 * 6.0;
constexpr double kPaperSeconds = 27.0 * 3600.0;
// The room the benchmarks sweep: furnished, closed, lit by a ceiling panel.
constexpr const char* kScene = "room:16";

struct SweepMeasurement {
  size_t voxels = 0, sides = 0, directions = 0;
  double secondsPerIteration = 0.0, visitsPerSecond = 0.0, bytesPerSide = 0.0;
};

// One sweep iteration of a whole solve (no first shot, so the time is the sweep's alone) at a
// voxel size.
SweepMeasurement measureSweep(const Scene& scene, float voxelSize, int sphereRadius,
                              Console& console) {
  VoxelRadiositySettings settings;
  settings.voxelSize = voxelSize;
  settings.sphereRadius = sphereRadius;
  settings.iterations = 1;
  settings.tolerance = 0.0;
  settings.directFirstShot = false;
  const VoxelRadiosity solution(
      scene, settings,
      console.progress(fmt::format("sweep {} at {:g} m voxels", scene.name, voxelSize)));
  console.finishProgress();
  const VoxelRadiosityStats& s = solution.stats();
  const double seconds = s.iterationSeconds.front();
  return {s.voxels,
          s.sides,
          s.directions,
          seconds,
          double(s.visits) / seconds,
          double(s.memoryBytes) / double(s.sides)};
}

constexpr int kRounds = 3;

std::string svgPlot(const std::vector<SweepMeasurement>& points, double slope) {
  LogLogPlot plot{fmt::format("Voxel sweep: seconds per iteration against voxels, log-log slope "
                              "{:.3f}",
                              slope),
                  "voxels",
                  "seconds per iteration",
                  "",
                  "s",
                  {}};
  for (const SweepMeasurement& p : points)
    plot.points.emplace_back(double(p.voxels), p.secondsPerIteration);
  return logLogSvg(plot);
}

}  // namespace

nlohmann::json benchVoxel(Console& console, size_t voxels, int sphereRadius, size_t pairStride) {
  const Scene scene = loadScene(kScene);
  // The default (a 24th of the directions, three times) takes an eighth of one iteration.
  const VoxelSweepRate m =
      measureVoxelSweepRate(scene, voxels, sphereRadius, pairStride, kRounds,
                            console.progress(fmt::format("sweep {} at {} voxels", kScene, voxels)));
  console.finishProgress();
  const double median = m.roundSeconds[m.roundSeconds.size() / 2];
  const double visitsPerSecond = m.visitsPerRound / median;
  const double bestVisitsPerSecond = m.visitsPerRound / m.roundSeconds.front();
  const double bytesPerSide = m.bytes / double(m.sides), bytesPerVoxel = m.bytes / double(m.voxels);
  const double paperSeconds = kPaperVisits / visitsPerSecond;
  return {
      {"scene", kScene},
      {"voxels", m.voxels},
      {"sides", m.sides},
      {"directions", m.directions},
      {"directions_swept", m.directionsSwept},
      {"seconds_per_round", median},
      {"rounds", kRounds},
      {"visits_per_s", visitsPerSecond},
      {"visits_per_s_best", bestVisitsPerSecond},
      {"bytes_per_side", bytesPerSide},
      {"bytes_per_voxel", bytesPerVoxel},
      {"paper_workload_s", paperSeconds},
      {"speedup_over_paper", kPaperSeconds / paperSeconds},
      {"summary",
       fmt::format(
           "{:.1f} M visits/s, median of {} rounds (fastest {:.1f}) ({} {} voxels, {} of R {}'s {} "
           "directions, {:.2f} s/round, {:.1f} B/side, {:.1f} B/voxel); "
           "paper workload (2e6 voxels, R 38, 6 it.) extrapolated: {:.0f} s = {:.0f}x the paper",
           visitsPerSecond * 1e-6, kRounds, bestVisitsPerSecond * 1e-6, kScene, m.voxels,
           m.directionsSwept, sphereRadius, m.directions, median, bytesPerSide, bytesPerVoxel,
           paperSeconds, kPaperSeconds / paperSeconds)}};
}

nlohmann::json benchVoxelScaling(Console& console, int sphereRadius, size_t maxVoxels,
                                 const std::string& outputDirectory) {
  // Larger rooms at one voxel size (2.5 cm): the scene grows with N, surfaces and furniture alike,
  // so the mix of voxels (flat, edge, corner) stays the same and only N changes.
  constexpr float kVoxelSize = 0.025f;
  // Each room is swept kRepeats times and its fastest sweep kept, the rooms taken in turn: this
  // machine's speed drifts by tens of percent from minute to minute, which one run per room (or
  // a room's runs back to back) turns into a wrong slope.
  constexpr int kRepeats = 3;
  std::vector<Scene> scenes;
  std::vector<int> rooms;
  for (int n : {2, 4, 8, 16, 32, 64, 128, 192, 256}) {
    Scene scene = loadScene(fmt::format("room:{}", n));
    // Stop at the first room that would be well past the limit at this voxel size.
    if (voxelSizeForCount(scene, size_t(1.3 * double(maxVoxels))) > kVoxelSize) break;
    scenes.push_back(std::move(scene));
    rooms.push_back(n);
  }
  std::vector<SweepMeasurement> points(scenes.size());
  for (int r = 0; r < kRepeats; ++r)
    for (size_t i = 0; i < scenes.size(); ++i) {
      const SweepMeasurement m = measureSweep(scenes[i], kVoxelSize, sphereRadius, console);
      if (r == 0 || m.secondsPerIteration < points[i].secondsPerIteration) points[i] = m;
    }
  if (points.empty())
    throw InputError("--scaling-max-voxels",
                     fmt::format("{} voxels is fewer than the smallest room "
                                 "(room:2) needs at 2.5 cm",
                                 maxVoxels));
  // Least-squares slope of log(time) against log(voxels).
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const auto& p : points) {
    const double x = std::log(double(p.voxels)), y = std::log(p.secondsPerIteration);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double k = double(points.size());
  const double slope = points.size() > 1 ? (k * sxy - sx * sy) / (k * sxx - sx * sx) : 0.0;

  std::string csv =
      "scene,voxels,sides,directions,seconds_per_iteration,visits_per_s,bytes_per_side\n";
  nlohmann::json rows = nlohmann::json::array();
  for (size_t i = 0; i < points.size(); ++i) {
    const SweepMeasurement& p = points[i];
    csv += fmt::format("room:{},{},{},{},{:.4f},{:.0f},{:.1f}\n", rooms[i], p.voxels, p.sides,
                       p.directions, p.secondsPerIteration, p.visitsPerSecond, p.bytesPerSide);
    rows.push_back({{"scene", fmt::format("room:{}", rooms[i])},
                    {"voxels", p.voxels},
                    {"seconds_per_iteration", p.secondsPerIteration},
                    {"visits_per_s", p.visitsPerSecond},
                    {"bytes_per_side", p.bytesPerSide}});
  }
  std::filesystem::create_directories(outputDirectory);
  const std::string table = (std::filesystem::path(outputDirectory) / "voxel_scaling.csv").string();
  const std::string plot = (std::filesystem::path(outputDirectory) / "voxel_scaling.svg").string();
  writeTextAtomically(table, csv);
  writeTextAtomically(plot, svgPlot(points, slope));
  return {
      {"scene", "room:N at 2.5 cm voxels"},
      {"sphere_radius", sphereRadius},
      {"points", rows},
      {"loglog_slope", slope},
      {"table", table},
      {"plot", plot},
      {"summary",
       fmt::format("log-log slope {:.3f} over {} rooms ({} to {} voxels, R {}); table {}, plot {}",
                   slope, points.size(), points.front().voxels, points.back().voxels, sphereRadius,
                   table, plot)}};
}

}  // namespace rad::cli
