#pragma once
// The light-transport method and its settings, shared by `render`, `solve`, `animate` and
// `serve`: each setting is a flag and a key of the scene's "solver" object; the flag wins, then
// the scene, then the method's default. Also the solve the commands run: progress, warnings and
// stats.

#include <radiosity/light_groups.h>
#include <radiosity/radiosity_engine.h>
#include <radiosity/radiosity_method.h>
#include <radiosity/run_stats.h>
#include <radiosity/scene.h>
#include <radiosity/solver_settings.h>

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "console.h"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace rad::cli {

/// Which methods a command offers and what it reads of their settings, so that its --help
/// lists only those.
struct MethodUse {
  /// The methods it offers: those with this capability (null: every one).
  bool MethodCapabilities::*needs = nullptr;
  std::string defaultMethod;        ///< the method it runs when neither flag nor scene says
  std::vector<std::string> unread;  ///< settings of those methods it does not read, by name
  bool groupScales = true;          ///< takes --group
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

  /// The method the settings chose, and its name.
  const RadiosityMethod& chosen() const { return radiosityMethod(settings_.method); }
  const std::string& method() const { return settings_.method; }
  const MethodSettings& settings() const { return settings_; }
  /// What the --group flags ask.
  const std::vector<GroupScale>& groupScales() const { return groupScales_; }

 private:
  SolverSettings given() const;
  void parseGroups(const Scene& scene);
  void addSetting(CLI::App& command, const SettingDeclaration& d);

  MethodUse use_;
  std::vector<std::string> methods_;  ///< offeredMethods(use_)
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
struct StatsReport {
  RunStats& stats;
  bool objectMeans = false;
};

/// Where a command's solution comes from: a solve, or the solution file `file` when it is set.
struct SolutionSource {
  std::span<const GroupScale> groups;  ///< the --group scales, applied after
  std::string file;
  double seconds = 0.0;  ///< where the dynamic objects are (their light is one more bounce)
};

/// Solves the engine's scene (RadiosityEngine::solve: with its dynamic objects at the source's
/// time) with a progress bar, or loads it from the source's file, scales its light groups as the
/// source asks, prints the method's warnings and reports its numbers. Throws what the method
/// throws.
std::unique_ptr<SurfaceSolution> solveSurfaces(const RadiosityEngine& engine,
                                               const SolutionSource& source, Console& console,
                                               const StatsReport& report);
/// A relighting by the engine's method for `lights`: solved with a progress bar, or started
/// from the solution file `solutionFile` when it is set; prints the solution's warnings.
/// Throws InputError for a method that does not relight.
std::unique_ptr<Relighting> startRelighting(const RadiosityEngine& engine,
                                            std::span<const Light> lights,
                                            const std::string& solutionFile,
                                            const RelightSettings& relight, Console& console,
                                            const std::function<void(double)>& alsoReport = {});
/// The methods a command offers, its default first.
std::vector<std::string> offeredMethods(const MethodUse& use);
/// The settings as a solution file records them: every one the method read, by name.
SolverSettings solvedWith(const MethodSettings& settings);

}  // namespace rad::cli
