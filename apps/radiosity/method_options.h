#pragma once
// The light-transport method and its settings, shared by `render` and `solve`: each setting is
// a flag and a key of the scene's "solver" object; the flag wins, then the scene, then the
// method's default. Also the solve both commands run: progress, warnings and stats.

#include <radiosity/patch_radiosity.h>
#include <radiosity/path_tracer.h>
#include <radiosity/scene.h>
#include <radiosity/voxel_radiosity.h>

#include "console.h"
#include "output/run_stats.h"

#include <string>
#include <vector>

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace rad::cli {

class MethodOptions {
 public:
  /// `methods` lists the methods the command accepts, the first being the default.
  MethodOptions(CLI::App& command, std::vector<std::string> methods);

  /// Fills the settings from the scene where no flag was given; throws InputError for a
  /// method the command does not offer.
  void resolve(const Scene& scene);

  const std::string& method() const { return method_; }
  const PathTracerSettings& pathTracer() const { return pathTracer_; }
  const VoxelRadiositySettings& voxel() const { return voxel_; }
  const PatchRadiositySettings& patch() const { return patch_; }

 private:
  std::vector<std::string> methods_;
  std::string method_;
  PathTracerSettings pathTracer_;
  VoxelRadiositySettings voxel_;
  PatchRadiositySettings patch_;
  /// The names given to the enum-valued flags; empty: not given.
  std::string estimatorName_, solverName_, shadingName_;
  CLI::Option *methodFlag_, *sppFlag_, *maxDepthFlag_, *seedFlag_;
  CLI::Option *voxelSizeFlag_, *voxelsFlag_, *radiusFlag_, *iterationsFlag_, *toleranceFlag_,
      *tangentFlag_, *firstShotFlag_, *directSamplesFlag_, *laterRadiusFlag_, *normalizeFlag_,
      *jitterFlag_, *tailFlag_;
  CLI::Option *patchSizeFlag_, *patchesFlag_, *estimatorFlag_, *ffRaysFlag_, *thresholdFlag_,
      *cacheDirFlag_, *solverFlag_, *maxIterationsFlag_, *shadingFlag_, *lightSamplesFlag_,
      *refineLevelsFlag_, *refineThresholdFlag_;
  void addPatchFlags(CLI::App& command);
  void resolvePatch(const Scene& scene);
};

/// Solves `scene` by the voxel method with a progress bar, prints the method's warnings and puts
/// its numbers in `stats`; the per-object means (stats.objects, a pass over every voxel side) only
/// if `objectMeans`, since only the stats file reports them. Throws what the solver throws.
VoxelRadiosity solveVoxels(const Scene& scene, const VoxelRadiositySettings& settings,
                           Console& console, RunStats& stats, bool objectMeans);
/// The same for the patch method.
PatchRadiosity solvePatches(const Scene& scene, const PatchRadiositySettings& settings,
                            Console& console, RunStats& stats, bool objectMeans);

}  // namespace rad::cli
