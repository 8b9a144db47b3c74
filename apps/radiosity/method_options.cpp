#include "method_options.h"

#include <radiosity/error.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>

namespace rad::cli {

MethodOptions::MethodOptions(CLI::App& c, std::vector<std::string> methods)
    : methods_(std::move(methods)), method_(methods_.front()) {
  methodFlag_ = c.add_option("--method", method_, "Light transport method (default: " + method_ + ")")
                    ->check(CLI::IsMember(methods_));
  sppFlag_ = c.add_option("--spp", pathTracer_.samplesPerPixel,
                          "Samples per pixel: paths (pathtrace, default 64) or camera rays (others)")
                 ->check(CLI::Range(1, 1 << 20));
  maxDepthFlag_ = c.add_option("--max-depth", pathTracer_.maxDepth, "Path tracer bounce limit")
                      ->check(CLI::Range(1, 100000));
  seedFlag_ = c.add_option("--seed", pathTracer_.seed, "Random seed (same seed, same result)");
  const std::string voxel = "Voxel method";
  voxelSizeFlag_ = c.add_option("--voxel-size", voxel_.voxelSize, "Voxel edge in scene units")
                       ->check(CLI::PositiveNumber)->group(voxel);
  voxelsFlag_ = c.add_option("--voxels", voxel_.targetVoxels,
                             "Approximate number of surface voxels (default 200000)")
                    ->check(CLI::Range(size_t(1), size_t(1) << 32))->group(voxel);
  radiusFlag_ = c.add_option("--sphere-radius", voxel_.sphereRadius,
                             "Radius R of the discrete sphere of directions (default 38: 14790)")
                    ->check(CLI::Range(1, 200))->group(voxel);
  iterationsFlag_ = c.add_option("--iterations", voxel_.iterations, "Sweeps over all directions (default 6)")
                        ->check(CLI::Range(1, 100000))->group(voxel);
  toleranceFlag_ = c.add_option("--tolerance", voxel_.tolerance,
                                "Stop once the relative change of B is below this")
                       ->check(CLI::NonNegativeNumber)->group(voxel);
  tangentFlag_ = c.add_flag("--tangent-correction,!--no-tangent-correction", voxel_.tangentCorrection,
                            "Look through voxels a line only grazes (default on)")->group(voxel);
  firstShotFlag_ = c.add_flag("--first-shot,!--no-first-shot", voxel_.directFirstShot,
                              "Direct light by shadow rays before the sweeps (default on)")->group(voxel);
  normalizeFlag_ = c.add_flag("--normalize,!--no-normalize", voxel_.normalize,
                              "Per-voxel normalization of the direction factors (default on)")->group(voxel);
  jitterFlag_ = c.add_flag("--jitter-lines,!--no-jitter-lines", voxel_.jitterLines,
                           "Shift each direction's lines every iteration (default on)")->group(voxel);
  directSamplesFlag_ = c.add_option("--direct-samples", voxel_.directSamples,
                                    "Shadow-ray samples per voxel side for the first shot (default 64)")
                           ->check(CLI::Range(1, 1 << 20))->group(voxel);
}

void MethodOptions::resolve(const Scene& scene) {
  const SolverSettings& s = scene.solver;
  auto take = [](CLI::Option* flag, auto& value, const auto& fromScene) {
    if (!*flag && fromScene) value = *fromScene;
  };
  take(methodFlag_, method_, s.method);
  if (std::find(methods_.begin(), methods_.end(), method_) == methods_.end())
    throw InputError(scene.name + ": /solver/method",
                     fmt::format("method '{}' is not available here (available: {})", method_,
                                 fmt::join(methods_, ", ")));
  if (method_ != "pathtrace" && !*sppFlag_) pathTracer_.samplesPerPixel = 4;
  take(sppFlag_, pathTracer_.samplesPerPixel, s.spp);
  take(maxDepthFlag_, pathTracer_.maxDepth, s.maxDepth);
  take(seedFlag_, pathTracer_.seed, s.seed);
  voxel_.seed = pathTracer_.seed;
  take(voxelSizeFlag_, voxel_.voxelSize, s.voxelSize);
  take(voxelsFlag_, voxel_.targetVoxels, s.voxels);
  take(radiusFlag_, voxel_.sphereRadius, s.sphereRadius);
  take(iterationsFlag_, voxel_.iterations, s.iterations);
  take(toleranceFlag_, voxel_.tolerance, s.tolerance);
  take(tangentFlag_, voxel_.tangentCorrection, s.tangentCorrection);
  take(firstShotFlag_, voxel_.directFirstShot, s.firstShot);
  take(directSamplesFlag_, voxel_.directSamples, s.directSamples);
}

void addVoxelStats(const VoxelRadiosity& solution, RunStats& stats) {
  const VoxelRadiosityStats& v = solution.stats();
  stats.methodDetails = {{"voxel_size", v.voxelSize},
                         {"cells", v.voxels},
                         {"sides", v.sides},
                         {"visits", v.visits},
                         {"visits_per_s", double(v.visits) / std::max(v.sweepSeconds, 1e-9)},
                         {"shadow_rays", v.shadowRays},
                         {"memory_bytes", v.memoryBytes},
                         {"bytes_per_side", double(v.memoryBytes) / double(std::max<size_t>(v.sides, 1))},
                         {"seconds", {{"voxelize", v.voxelizeSeconds}, {"first_shot", v.directSeconds},
                                      {"sweeps", v.sweepSeconds}}}};
  stats.counts.voxels = v.sides;
  stats.counts.directions = v.directions;
  stats.counts.rays += v.shadowRays;
  stats.timingsSeconds.prepare = v.voxelizeSeconds;
  stats.timingsSeconds.solve = v.directSeconds + v.sweepSeconds;
  stats.iterations = int(v.residuals.size());
  stats.residual = v.residuals.empty() ? 0.0 : v.residuals.back();
  stats.residuals = v.residuals;
  stats.objects = solution.objectRadiometry();
}

}  // namespace rad::cli
