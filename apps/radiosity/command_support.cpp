#include "command_support.h"

#include <radiosity/error.h>
#include <radiosity/scene_loader.h>

#include <CLI/CLI.hpp>
#include <filesystem>

#include "core/memory_usage.h"

namespace rad::cli {

void addSceneArgument(CLI::App& command, std::string& scene) {
  command
      .add_option("scene", scene,
                  "Scene file (.json .obj .gltf .glb) or built-in: cornell, "
                  "cornell-spot, room:N")
      ->required();
}

void addStatsOption(CLI::App& command, std::string& path) {
  command.add_option("--stats", path, "Write the run's numbers to this JSON file");
}

void addTimeOption(CLI::App& command, double& seconds) {
  command
      .add_option("--time", seconds,
                  "Seconds into the lights' animation (spins and keyframed paths; default 0)")
      ->check(CLI::Number);
}

// A check that the option's value is a number at least zero.
const CLI::Validator& nonNegativeNumber() {
  static const CLI::Validator check(
      [](std::string& input) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(input, value)) return "'" + input + "' is not a number";
        return value >= 0.0 ? "" : input + " is below 0";
      },
      "NONNEGATIVE");
  return check;
}

Scene loadSceneForCommand(const std::string& name, double seconds, Console& console,
                          RunStats& stats) {
  Stopwatch loadTime;
  Scene scene = loadScene(name);
  scene.lights = scene.lightsAt(seconds);
  stats.timingsSeconds.load = loadTime.seconds();
  for (const std::string& w : scene.warnings) console.warn(scene.name + ": " + w);
  requireEmitters(scene);
  stats.counts.triangles = scene.triangles.size();
  return scene;
}

void checkSolutionOutput(const std::string& path) {
  const std::filesystem::path file(path);
  if (file.extension() != ".rad") throw InputError("--save " + path, "expected a .rad file");
  const std::filesystem::path dir = file.parent_path();
  std::error_code ec;
  if (!dir.empty() && !std::filesystem::is_directory(dir, ec))
    throw InputError("--save " + path, "its directory " + dir.string() + " does not exist");
}

void writeStatsFile(const std::string& path, const Scene& scene, const std::string& sceneName,
                    const std::string& method, double totalSeconds, RunStats& stats) {
  stats.scene = sceneName;
  stats.method = method;
  stats.emittedPower = scene.emittedPower();
  if (!stats.lightGroups.empty()) {
    stats.emittedPower = Color(0.0f);
    for (const RunStats::LightGroupEntry& g : stats.lightGroups) stats.emittedPower += g.power;
  }
  if (!stats.objects.empty())
    stats.absorbedPower = absorbedPower(scene, stats.objects, stats.emissionScales);
  stats.timingsSeconds.total = totalSeconds;
  stats.memoryPeakBytes = peakResidentBytes();
  writeRunStats(path, stats);
}

}  // namespace rad::cli
