#include "method_options.h"

#include "command_support.h"

#include <radiosity/error.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

namespace rad::cli {

namespace {

// What a choice means, for --help, where its name does not say it.
const char* helpOf(PatchFormFactorEstimator e) {
  switch (e) {
    case PatchFormFactorEstimator::Hemisphere:
      return "rays from each patch";
    case PatchFormFactorEstimator::Pairwise:
      return "point pairs";
    case PatchFormFactorEstimator::Exact:
      return "point-to-polygon, visibility rays";
  }
  return "";
}
const char* helpOf(PatchSolverKind) { return ""; }
const char* helpOf(PatchShading) { return ""; }

// The flag, checked against the library's table of names (patch_radiosity.h), with the names
// (and the default) listed in its help: "<what>: a (help, default), b, c".
template <class Enum, size_t N>
CLI::Option* addNamedOption(CLI::App& command, const std::string& flag, std::string& name,
                            const NamedChoice<Enum> (&choices)[N], Enum defaultValue,
                            const std::string& what) {
  std::vector<std::string> items;
  for (const NamedChoice<Enum>& c : choices) {
    std::string note = helpOf(c.value);
    if (c.value == defaultValue) note += note.empty() ? "default" : ", default";
    items.push_back(note.empty() ? c.name : fmt::format("{} ({})", c.name, note));
  }
  return command.add_option(flag, name, fmt::format("{}: {}", what, fmt::join(items, ", ")))
      ->check(CLI::IsMember(choiceNames(choices)));
}

// The value a name stands for. The flag and the scene loader check names against the same
// table, so an unknown one here is a bug; it is still reported as bad input, named.
template <class Enum, size_t N>
Enum valueOf(const NamedChoice<Enum> (&choices)[N], const std::string& name,
             const std::string& where) {
  if (const std::optional<Enum> value = choiceNamed(choices, name)) return *value;
  throw InputError(where, fmt::format("'{}' is not one of {}", name, fmt::join(choiceNames(choices), ", ")));
}

// The flag's value if it was given, else the scene's if it has one; `value` as it is otherwise.
template <class T, class U>
void takeUnlessFlagged(const CLI::Option* flag, T& value, const std::optional<U>& fromScene) {
  if (!*flag && fromScene) value = *fromScene;
}

// Solves with a progress bar, then prints the method's warnings (settings that lose light, a
// cache file that could not be used).
template <class Solution, class Settings>
Solution solveShowingProgress(const Scene& scene, const Settings& settings, const std::string& label,
                              Console& console) {
  Solution solution(scene, settings, console.progress(label));
  console.finishProgress();
  for (const std::string& w : solution.stats().warnings) console.warn(w);
  return solution;
}

}  // namespace

MethodOptions::MethodOptions(CLI::App& c, std::vector<std::string> methods)
    : methods_(std::move(methods)), method_(methods_.front()) {
  methodFlag_ = c.add_option("--method", method_, "Light transport method (default: " + method_ + ")")
                    ->check(CLI::IsMember(methods_));
  sppFlag_ = c.add_option("--spp", pathTracer_.samplesPerPixel,
                          "Samples per pixel: paths (pathtrace, default 64) or camera rays "
                          "(others, default 16, one per cell of a 4 x 4 grid)")
                 ->check(CLI::Range(1, 1 << 20));
  maxDepthFlag_ = c.add_option("--max-depth", pathTracer_.maxDepth, "Path tracer bounce limit")
                      ->check(CLI::Range(1, 100000));
  seedFlag_ = c.add_option("--seed", pathTracer_.seed, "Random seed (same seed, same result)");
  const std::string voxel = "Voxel method";
  voxelSizeFlag_ = c.add_option("--voxel-size", voxel_.voxelSize, "Voxel edge in scene units")
                       ->check(positiveNumber())->group(voxel);
  voxelsFlag_ = c.add_option("--voxels", voxel_.targetVoxels,
                             "Approximate number of surface voxels (default 200000)")
                    ->check(CLI::Range(size_t(1), size_t(1) << 32))->group(voxel);
  radiusFlag_ = c.add_option("--sphere-radius", voxel_.sphereRadius,
                             "Radius R of the discrete sphere of directions (default 38: 14790)")
                    ->check(CLI::Range(1, 200))->group(voxel);
  iterationsFlag_ = c.add_option("--iterations", voxel_.iterations, "Sweeps over all directions (default 6)")
                        ->check(CLI::Range(1, 100000))->group(voxel);
  toleranceFlag_ = c.add_option("--tolerance", voxel_.tolerance,
                                "Stop once the relative residual is below this (voxel: the "
                                "power an iteration adds over B's; patch: default 1e-3)")
                       ->check(nonNegativeNumber())->group(voxel);
  tangentFlag_ = c.add_flag("--tangent-correction,!--no-tangent-correction", voxel_.tangentCorrection,
                            "Look through voxels a line only grazes (default on)")->group(voxel);
  firstShotFlag_ = c.add_flag("--first-shot,!--no-first-shot", voxel_.directFirstShot,
                              "Direct light by shadow rays before the sweeps (default on)")->group(voxel);
  normalizeFlag_ = c.add_flag("--normalize,!--no-normalize", voxel_.normalize,
                              "Per-voxel normalization of the direction factors (default on)")->group(voxel);
  jitterFlag_ = c.add_flag("--jitter-lines,!--no-jitter-lines", voxel_.jitterLines,
                           "Shift each direction's lines every iteration (default on)")->group(voxel);
  laterRadiusFlag_ = c.add_option("--later-sphere-radius", voxel_.laterSphereRadius,
                                  "Sphere radius for the sweeps after the first, whose light is "
                                  "smoother (default: --sphere-radius)")
                        ->check(CLI::Range(1, 200))->group(voxel);
  tailFlag_ = c.add_flag("--tail-estimate,!--no-tail-estimate", voxel_.estimateTail,
                         "Add the bounces after the last iteration, extrapolated (default on)")
                  ->group(voxel);
  directSamplesFlag_ = c.add_option("--direct-samples", voxel_.directSamples,
                                    "Shadow-ray samples per voxel side for the first shot (default 64)")
                           ->check(CLI::Range(1, 1 << 20))->group(voxel);
  addPatchFlags(c);
}

void MethodOptions::addPatchFlags(CLI::App& c) {
  const std::string patch = "Patch method";
  patchSizeFlag_ = c.add_option("--patch-size", patch_.patchSize,
                                 "Longest patch edge in scene units")
                       ->check(positiveNumber())->group(patch);
  patchesFlag_ = c.add_option("--patches", patch_.targetPatches,
                              "Approximate number of patches (default 4000)")
                     ->check(CLI::Range(size_t(1), size_t(1) << 32))->group(patch);
  const PatchRadiositySettings defaults;
  estimatorFlag_ = addNamedOption(c, "--ff-estimator", estimatorName_, kFormFactorEstimatorNames,
                                  defaults.estimator, "Form factors by")->group(patch);
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
  solverFlag_ = addNamedOption(c, "--solver", solverName_, kPatchSolverNames, defaults.solver,
                               "Linear solver")->group(patch);
  maxIterationsFlag_ = c.add_option("--max-iterations", patch_.maxIterations,
                                    "Solver sweeps at most (progressive: shots / patches; "
                                    "default 1000)")
                           ->check(CLI::Range(1, 100000000))->group(patch);
  shadingFlag_ = addNamedOption(c, "--shading", shadingName_, kPatchShadingNames, defaults.shading,
                                "Rendering of the patches")->group(patch);
  lightSamplesFlag_ = c.add_option("--light-samples", patch_.lightSamples,
                                   "Points per patch (rounded up to a square) at which point, spot "
                                   "and IES light is averaged (default 16)")
                          ->check(CLI::Range(1, 1 << 16))->group(patch);
  refineLevelsFlag_ = c.add_option("--refine-levels", patch_.refineLevels,
                                   "Adaptive subdivision for point, spot and IES lights: levels "
                                   "below the base patch size at most (default 2; 0: none)")
                          ->check(CLI::Range(0, 8))->group(patch);
  refineThresholdFlag_ = c.add_option("--refine-threshold", patch_.refineThreshold,
                                      "Split neighbouring patches whose direct light differs by "
                                      "more than this, relative (default 0.5)")
                             ->check(positiveNumber())->group(patch);
}

void MethodOptions::resolvePatch(const Scene& scene) {
  const SolverSettings& s = scene.solver;
  auto takeNamed = [&](const CLI::Option* flag, std::string& name,
                       const std::optional<std::string>& fromScene, const char* key, auto& value,
                       const auto& values) {
    takeUnlessFlagged(flag, name, fromScene);
    if (!name.empty()) value = valueOf(values, name, scene.name + ": /solver/" + key);
  };
  patch_.seed = pathTracer_.seed;
  takeUnlessFlagged(patchSizeFlag_, patch_.patchSize, s.patchSize);
  takeUnlessFlagged(patchesFlag_, patch_.targetPatches, s.patches);
  takeNamed(estimatorFlag_, estimatorName_, s.ffEstimator, "ff_estimator", patch_.estimator,
            kFormFactorEstimatorNames);
  takeUnlessFlagged(ffRaysFlag_, patch_.formFactorRays, s.ffRays);
  if (!*thresholdFlag_ && s.ffThreshold) patch_.formFactorThreshold = float(*s.ffThreshold);
  if (!*cacheDirFlag_) patch_.cacheDir = s.cacheDir.value_or(defaultPatchCacheDir());
  if (patch_.cacheDir == "none") patch_.cacheDir.clear();
  takeNamed(solverFlag_, solverName_, s.patchSolver, "solver", patch_.solver, kPatchSolverNames);
  takeUnlessFlagged(maxIterationsFlag_, patch_.maxIterations, s.maxIterations);
  takeNamed(shadingFlag_, shadingName_, s.shading, "shading", patch_.shading, kPatchShadingNames);
  takeUnlessFlagged(lightSamplesFlag_, patch_.lightSamples, s.lightSamples);
  takeUnlessFlagged(refineLevelsFlag_, patch_.refineLevels, s.refineLevels);
  takeUnlessFlagged(refineThresholdFlag_, patch_.refineThreshold, s.refineThreshold);
  // --tolerance is shared with the voxel method, whose default (0: run every sweep) differs.
  patch_.tolerance = *toleranceFlag_ ? voxel_.tolerance : s.tolerance.value_or(1e-3);
}

void MethodOptions::resolve(const Scene& scene) {
  const SolverSettings& s = scene.solver;
  takeUnlessFlagged(methodFlag_, method_, s.method);
  if (std::find(methods_.begin(), methods_.end(), method_) == methods_.end())
    throw InputError(scene.name + ": /solver/method",
                     fmt::format("method '{}' is not available here (available: {})", method_,
                                 fmt::join(methods_, ", ")));
  // A camera ray costs one lookup: 16 stratified ones smooth the edges (4 left a lamp's
  // nearly level edge stepped), for 0.1 s more at 256 x 256 with voxels, 1 s at 1024 x 1024.
  if (method_ != "pathtrace" && !*sppFlag_) pathTracer_.samplesPerPixel = 16;
  takeUnlessFlagged(sppFlag_, pathTracer_.samplesPerPixel, s.spp);
  takeUnlessFlagged(maxDepthFlag_, pathTracer_.maxDepth, s.maxDepth);
  takeUnlessFlagged(seedFlag_, pathTracer_.seed, s.seed);
  voxel_.seed = pathTracer_.seed;
  takeUnlessFlagged(voxelSizeFlag_, voxel_.voxelSize, s.voxelSize);
  takeUnlessFlagged(voxelsFlag_, voxel_.targetVoxels, s.voxels);
  takeUnlessFlagged(radiusFlag_, voxel_.sphereRadius, s.sphereRadius);
  takeUnlessFlagged(iterationsFlag_, voxel_.iterations, s.iterations);
  takeUnlessFlagged(toleranceFlag_, voxel_.tolerance, s.tolerance);
  takeUnlessFlagged(tangentFlag_, voxel_.tangentCorrection, s.tangentCorrection);
  takeUnlessFlagged(firstShotFlag_, voxel_.directFirstShot, s.firstShot);
  takeUnlessFlagged(laterRadiusFlag_, voxel_.laterSphereRadius, s.laterSphereRadius);
  takeUnlessFlagged(normalizeFlag_, voxel_.normalize, s.normalize);
  takeUnlessFlagged(jitterFlag_, voxel_.jitterLines, s.jitterLines);
  takeUnlessFlagged(tailFlag_, voxel_.estimateTail, s.tailEstimate);
  takeUnlessFlagged(directSamplesFlag_, voxel_.directSamples, s.directSamples);
  resolvePatch(scene);
}

VoxelRadiosity solveVoxels(const Scene& scene, const VoxelRadiositySettings& settings,
                           Console& console, RunStats& stats, bool objectMeans) {
  VoxelRadiosity solution =
      solveShowingProgress<VoxelRadiosity>(scene, settings, "voxel solve", console);
  const VoxelRadiosityStats& v = solution.stats();
  stats.methodDetails = {{"voxel_size", v.voxelSize},
                         {"cells", v.voxels},
                         {"sides", v.sides},
                         {"visits", v.visits},
                         {"visits_per_s", double(v.visits) / std::max(v.sweepSeconds, 1e-9)},
                         {"shadow_rays", v.shadowRays},
                         {"sweep_threads", v.sweepThreads},
                         {"tail_share", v.tailShare},
                         {"later_directions", v.laterDirections},
                         {"memory_bytes", v.memoryBytes},
                         {"bytes_per_side", double(v.memoryBytes) / double(std::max<size_t>(v.sides, 1))},
                         {"bytes_per_voxel", double(v.memoryBytes) / double(std::max<size_t>(v.voxels, 1))},
                         {"seconds", {{"voxelize", v.voxelizeSeconds}, {"first_shot", v.directSeconds},
                                      {"sweeps", v.sweepSeconds}, {"iterations", v.iterationSeconds}}}};
  stats.counts.voxels = v.sides;
  stats.counts.directions = v.directions;
  stats.counts.rays += v.shadowRays;
  stats.timingsSeconds.prepare = v.voxelizeSeconds;
  stats.timingsSeconds.solve = v.directSeconds + v.sweepSeconds;
  stats.iterations = int(v.residuals.size());
  stats.residual = v.residuals.empty() ? 0.0 : v.residuals.back();
  stats.residuals = v.residuals;
  if (objectMeans) stats.objects = solution.objectRadiometry();
  return solution;
}

PatchRadiosity solvePatches(const Scene& scene, const PatchRadiositySettings& settings,
                            Console& console, RunStats& stats, bool objectMeans) {
  PatchRadiosity solution =
      solveShowingProgress<PatchRadiosity>(scene, settings, "patch solve", console);
  const PatchRadiosityStats& p = solution.stats();
  stats.methodDetails = {{"patch_size", p.patchSize},
                         {"nodes", p.nodes},
                         {"vertices", p.vertices},
                         {"table_entries", p.nonZeros},
                         {"exact_columns", p.exactColumns},
                         {"table_bytes", p.tableBytes},
                         {"dropped_entry_fraction", p.droppedEntryFraction},
                         {"dropped_sum_fraction", p.droppedSumFraction},
                         {"dropped_worst_row_fraction", p.droppedWorstRowFraction},
                         {"rows_dropping_over_1_percent", p.rowsDroppingOverOnePercent},
                         {"row_sum", {{"min", p.rowSumMin}, {"mean", p.rowSumMean}, {"max", p.rowSumMax}}},
                         {"cache_loaded", p.cacheLoaded},
                         {"cache_file", p.cacheFile},
                         {"solver", p.solver},
                         {"shots", p.shots},
                         {"rays_per_s", double(p.rays - p.lightRays) / std::max(p.formFactorSeconds, 1e-9)},
                         {"light_rays", p.lightRays},
                         {"base_patches", p.basePatches},
                         {"refined_splits", p.refinedSplits},
                         {"refine_rounds", p.refineRounds},
                         {"light_rays_per_s", double(p.lightRays) / std::max(p.lightSeconds, 1e-9)},
                         {"memory_bytes", p.memoryBytes},
                         {"seconds", {{"mesh", p.meshSeconds}, {"form_factors", p.formFactorSeconds},
                                      {"cache_load", p.cacheLoadSeconds}, {"light", p.lightSeconds},
                                      {"solve", p.solveSeconds}}}};
  stats.counts.patches = p.patches;
  stats.counts.rays += p.rays;
  stats.timingsSeconds.prepare = p.meshSeconds + p.formFactorSeconds + p.cacheLoadSeconds;
  stats.timingsSeconds.solve = p.lightSeconds + p.solveSeconds;
  stats.iterations = p.iterations;
  stats.residual = p.residuals.empty() ? 0.0 : p.residuals.back();
  stats.residuals = p.residuals;
  if (objectMeans) stats.objects = solution.objectRadiometry();
  return solution;
}

}  // namespace rad::cli
