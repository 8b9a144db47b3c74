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
                                "Stop once the relative change of B (voxel) or the relative "
                                "residual (patch, default 1e-3) is below this")
                       ->check(CLI::NonNegativeNumber)->group(voxel);
  tangentFlag_ = c.add_flag("--tangent-correction,!--no-tangent-correction", voxel_.tangentCorrection,
                            "Look through voxels a line only grazes (default on)")->group(voxel);
  firstShotFlag_ = c.add_flag("--first-shot,!--no-first-shot", voxel_.directFirstShot,
                              "Direct light by shadow rays before the sweeps (default on)")->group(voxel);
  c.add_flag("--normalize,!--no-normalize", voxel_.normalize,
                              "Per-voxel normalization of the direction factors (default on)")->group(voxel);
  c.add_flag("--jitter-lines,!--no-jitter-lines", voxel_.jitterLines,
                           "Shift each direction's lines every iteration (default on)")->group(voxel);
  directSamplesFlag_ = c.add_option("--direct-samples", voxel_.directSamples,
                                    "Shadow-ray samples per voxel side for the first shot (default 64)")
                           ->check(CLI::Range(1, 1 << 20))->group(voxel);
  addPatchFlags(c);
}

void MethodOptions::addPatchFlags(CLI::App& c) {
  const std::string patch = "Patch method";
  patchSizeFlag_ = c.add_option("--patch-size", patch_.patchSize,
                                 "Longest patch edge in scene units")
                       ->check(CLI::PositiveNumber)->group(patch);
  patchesFlag_ = c.add_option("--patches", patch_.targetPatches,
                              "Approximate number of patches (default 4000)")
                     ->check(CLI::Range(size_t(1), size_t(1) << 32))->group(patch);
  estimatorFlag_ = c.add_option("--ff-estimator", estimator_,
                                "Form factors by: hemisphere (rays from each patch, default), "
                                "pairwise (point pairs), exact (point-to-polygon, visibility "
                                "rays)")
                       ->check(CLI::IsMember({"hemisphere", "pairwise", "exact"}))->group(patch);
  ffRaysFlag_ = c.add_option("--ff-rays", patch_.formFactorRays,
                             "Rays per patch (hemisphere, default 256), point pairs per patch pair "
                             "(pairwise) or points per patch (exact)")
                    ->check(CLI::Range(1, 1 << 24))->group(patch);
  thresholdFlag_ = c.add_option("--ff-threshold", patch_.formFactorThreshold,
                                "Drop form factors below this (default 0: keep all)")
                       ->check(CLI::Range(0.0, 0.999999))->group(patch);
  cacheDirFlag_ = c.add_option("--cache-dir", patch_.cacheDir,
                               "Form-factor cache directory (default $XDG_CACHE_HOME/radiosity, "
                               "else ~/.cache/radiosity; none: no cache)")->group(patch);
  solverFlag_ = c.add_option("--solver", solver_,
                             "Linear solver: gauss-seidel (default), jacobi, progressive")
                    ->check(CLI::IsMember({"jacobi", "gauss-seidel", "progressive"}))->group(patch);
  maxIterationsFlag_ = c.add_option("--max-iterations", patch_.maxIterations,
                                    "Solver sweeps at most (progressive: shots / patches; "
                                    "default 1000)")
                           ->check(CLI::Range(1, 100000000))->group(patch);
  shadingFlag_ = c.add_option("--shading", shading_, "Rendering: smooth (default) or flat patches")
                     ->check(CLI::IsMember({"smooth", "flat"}))->group(patch);
}

void MethodOptions::resolvePatch(const Scene& scene) {
  const SolverSettings& s = scene.solver;
  auto take = [](CLI::Option* flag, auto& value, const auto& fromScene) {
    if (!*flag && fromScene) value = *fromScene;
  };
  patch_.seed = pathTracer_.seed;
  take(patchSizeFlag_, patch_.patchSize, s.patchSize);
  take(patchesFlag_, patch_.targetPatches, s.patches);
  take(estimatorFlag_, estimator_, s.ffEstimator);
  take(ffRaysFlag_, patch_.formFactorRays, s.ffRays);
  if (!*thresholdFlag_ && s.ffThreshold) patch_.formFactorThreshold = float(*s.ffThreshold);
  if (!*cacheDirFlag_) patch_.cacheDir = s.cacheDir.value_or(defaultPatchCacheDir());
  if (patch_.cacheDir == "none") patch_.cacheDir.clear();
  take(solverFlag_, solver_, s.patchSolver);
  take(maxIterationsFlag_, patch_.maxIterations, s.maxIterations);
  take(shadingFlag_, shading_, s.shading);
  // --tolerance is shared with the voxel method, whose default (0: run every sweep) differs.
  patch_.tolerance = *toleranceFlag_ ? voxel_.tolerance : s.tolerance.value_or(1e-3);
  patch_.estimator = estimator_ == "pairwise" ? PatchFormFactorEstimator::Pairwise
                     : estimator_ == "exact"  ? PatchFormFactorEstimator::Exact
                                              : PatchFormFactorEstimator::Hemisphere;
  patch_.solver = solver_ == "jacobi"        ? PatchSolverKind::Jacobi
                  : solver_ == "progressive" ? PatchSolverKind::Progressive
                                             : PatchSolverKind::GaussSeidel;
  patch_.shading = shading_ == "flat" ? PatchShading::Flat : PatchShading::Smooth;
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
  resolvePatch(scene);
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

namespace rad::cli {

void addPatchStats(const PatchRadiosity& solution, RunStats& stats) {
  const PatchRadiosityStats& p = solution.stats();
  stats.methodDetails = {{"patch_size", p.patchSize},
                         {"nodes", p.nodes},
                         {"vertices", p.vertices},
                         {"table_entries", p.nonZeros},
                         {"table_bytes", p.tableBytes},
                         {"dropped_entry_fraction", p.droppedEntryFraction},
                         {"dropped_sum_fraction", p.droppedSumFraction},
                         {"row_sum", {{"min", p.rowSumMin}, {"mean", p.rowSumMean}, {"max", p.rowSumMax}}},
                         {"cache_loaded", p.cacheLoaded},
                         {"cache_file", p.cacheFile},
                         {"solver", p.solver},
                         {"shots", p.shots},
                         {"rays_per_s", double(p.rays) / std::max(p.formFactorSeconds, 1e-9)},
                         {"memory_bytes", p.memoryBytes},
                         {"seconds", {{"mesh", p.meshSeconds}, {"form_factors", p.formFactorSeconds},
                                      {"cache_load", p.cacheLoadSeconds}, {"solve", p.solveSeconds}}}};
  stats.counts.patches = p.patches;
  stats.counts.rays += p.rays;
  stats.timingsSeconds.prepare = p.meshSeconds + p.formFactorSeconds + p.cacheLoadSeconds;
  stats.timingsSeconds.solve = p.solveSeconds;
  stats.iterations = p.iterations;
  stats.residual = p.residuals.empty() ? 0.0 : p.residuals.back();
  stats.residuals = p.residuals;
  stats.objects = solution.objectRadiometry();
}

}  // namespace rad::cli
