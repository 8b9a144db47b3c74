#pragma once
// The light-transport method and its settings, shared by `render` and `solve`: each setting is
// a flag and a key of the scene's "solver" object; the flag wins, then the scene, then the
// method's default. Also the solve both commands run: progress, warnings and stats.

#include <radiosity/light_groups.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/path_tracer.h>
#include <radiosity/relighter.h>
#include <radiosity/scene.h>
#include <radiosity/solver_settings.h>
#include <radiosity/voxel_radiosity.h>

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "console.h"
#include "output/run_stats.h"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace rad::cli {

/// What a command reads of the methods' settings, so that its --help lists only those.
struct MethodUse {
  std::vector<std::string> methods;  ///< the methods it offers, the first the default
  std::vector<std::string> unread;   ///< settings of those methods it does not read, by name
  bool groupScales = true;           ///< takes --group
};

class MethodOptions {
 public:
  /// Adds a flag for every declared setting (solver_settings.h) that one of the command's
  /// methods reads and the command does not leave unread, --method when it offers more than
  /// one, and --group.
  MethodOptions(CLI::App& command, MethodUse use);

  /// Resolves the settings: the flags given, then the scene's "solver" values, then the
  /// methods' defaults; any --group solves the light groups apart. Throws InputError for a
  /// method the command does not offer or a --group that names no group of the scene.
  void resolve(const Scene& scene);
  /// Resolves the settings a solution file was solved with (the method's flags and the scene's
  /// "solver" values are not for this run, and are warned of; --cache-dir, --spp and --seed,
  /// which are the run's own, and --group still apply). Throws InputError for a bad file.
  void resolveFromSolution(const Scene& scene, const std::string& path, Console& console);
  /// resolveFromSolution when `solutionFile` is set (--solution), else resolve; then keeps the
  /// cache directory under --cache-max-mb (trimCache).
  void resolve(const Scene& scene, const std::string& solutionFile, Console& console);
  /// Removes the cache directory's least recently used files beyond --cache-max-mb.
  void trimCache(Console& console) const;

  const std::string& method() const { return settings_.method; }
  const MethodSettings& settings() const { return settings_; }
  const PathTracerSettings& pathTracer() const { return settings_.pathTracer; }
  const VoxelRadiositySettings& voxel() const { return settings_.voxel; }
  const PatchRadiositySettings& patch() const { return settings_.patch; }
  /// What the --group flags ask.
  const std::vector<GroupScale>& groupScales() const { return groupScales_; }

 private:
  SolverSettings given() const;
  void parseGroups(const Scene& scene);
  void addSetting(CLI::App& command, const SettingDeclaration& d);

  std::vector<std::string> methods_;
  std::vector<std::string> groupText_;
  std::vector<GroupScale> groupScales_;
  MethodSettings settings_;
  /// What each flag was given, by setting name (std::map: CLI11 keeps pointers to them).
  std::map<std::string, std::string> text_;
  std::map<std::string, bool> switches_;
  std::map<std::string, CLI::Option*> options_;  ///< the settings the command offers, by name
};

/// What a solve of the commands reports besides the solution: its numbers, and the per-object
/// means (stats.objects, a pass over every element) only if `objectMeans`, since only the stats
/// file reports them.
struct SolveReport {
  RunStats& stats;
  bool objectMeans = false;
};

/// Where a command's solution comes from: a solve, or the solution file `file` when it is set.
struct SolutionSource {
  std::span<const GroupScale> groups;  ///< the --group scales, applied after
  std::string file;
  double seconds = 0.0;  ///< where the dynamic objects are (their light is one more bounce)
};

/// Solves `scene` (through `caster`, the run's one ray caster) by the voxel method with a
/// progress bar, or loads it from the source's file, scales its light groups as the source
/// asks, prints the method's warnings and reports its numbers. With dynamic objects, solves again
/// with the light they reflect (dynamicObjectLights) as lights. Throws what the solver throws.
VoxelRadiosity solveVoxels(const Scene& scene, const RayCaster& caster,
                           const VoxelRadiositySettings& settings, const SolutionSource& source,
                           Console& console, const SolveReport& report);
/// The same for the patch method.
PatchRadiosity solvePatches(const Scene& scene, const RayCaster& caster,
                            const PatchRadiositySettings& settings, const SolutionSource& source,
                            Console& console, const SolveReport& report);
/// A relighter of `model` for `lights`: solved with a progress bar, or started from the solution
/// file `solutionFile` when it is set; prints the solution's warnings.
Relighter startRelighter(const PatchModel& model, std::span<const Light> lights,
                         const std::string& solutionFile, const RelightSettings& settings,
                         Console& console, const std::function<void(double)>& alsoReport = {});
/// The settings as a solution file records them: every one the method read, by name.
SolverSettings solvedWith(const MethodSettings& settings);

}  // namespace rad::cli
