#pragma once
// Steps shared by the commands that compute light transport (render, solve, animate, serve).

#include <radiosity/run_stats.h>
#include <radiosity/scene.h>

#include <span>
#include <string>
#include <utility>

#include "console.h"

namespace CLI {
class App;
class Validator;
}  // namespace CLI

namespace rad::cli {

/// The SCENE argument every command takes: a scene file or a built-in name.
void addSceneArgument(CLI::App& command, std::string& scene);
/// The --stats FILE option of the commands that compute light transport (see writeStatsFile).
void addStatsOption(CLI::App& command, std::string& path);

/// The --time SECONDS option: the instant of the scene's light animation to compute.
void addTimeOption(CLI::App& command, double& seconds);

/// A check of a numeric option whose message says what was expected ("--object-points: -1 is
/// below 0"), where CLI11's NonNegativeNumber prints its range's bound (a 309-digit largest
/// double). The methods' settings have their declarations' checks (solver_settings.h).
const CLI::Validator& nonNegativeNumber();
/// The same for a finite number in [lo, hi] (CLI11's Range lets "nan" through: every comparison
/// with it is false).
CLI::Validator finiteNumberIn(double lo, double hi);
/// A check that a path's value is not empty: `--solution ""` is a mistake (a variable left
/// unset), not "no solution" (render then path-traced without a word).
const CLI::Validator& nonEmptyPath();

/// Loads the scene with its lights as they are `seconds` into their animation, prints its
/// warnings, refuses a scene with nothing that emits (a black result), and records the load time
/// and the triangle count.
Scene loadSceneForCommand(const std::string& name, double seconds, Console& console,
                          RunStats& stats);

/// Refuses, before any work, an output path (`option` names it in the message: "--stats") whose
/// directory does not exist or cannot be written, or that is a directory: an hour's solve must
/// not end in "cannot write". Empty paths (the output not asked for) pass.
void checkOutputPath(const std::string& option, const std::string& path);

/// Refuses two outputs of one run that name the same file (one would overwrite the other):
/// throws InputError naming both options. Pairs of option and path; empty paths are skipped.
void checkDistinctOutputs(std::span<const std::pair<std::string, std::string>> outputs);
/// checkOutputPath for a solution file name (--save), which must also be .rad.
void checkSolutionOutput(const std::string& path);

/// The exit status of a command once its outputs are written: 0, or 130 with a message when
/// Ctrl-C came while they were written (each is whole: outputs are written atomically).
int statusAfterOutputs(Console& console);

/// Completes the stats (scene, method, emitted power, total time, peak memory, the warnings
/// given so far) and writes them.
void writeStatsFile(const std::string& path, const Scene& scene, const std::string& sceneName,
                    const std::string& method, double totalSeconds, const Console& console,
                    RunStats& stats);

}  // namespace rad::cli
