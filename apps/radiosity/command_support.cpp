#include "command_support.h"

#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/process_memory.h>
#include <radiosity/scene_loader.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "mpi_processes.h"

namespace rad::cli {

void addSceneArgument(CLI::App& command, std::string& scene) {
  command
      .add_option("scene", scene,
                  "Scene file (.json .obj .gltf .glb) or built-in: cornell, "
                  "cornell-spot, room:N, atrium:N, atrium-textured:N")
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
  static const CLI::Validator check = finiteNumberIn(0.0, HUGE_VAL).name("NONNEGATIVE");
  return check;
}

const CLI::Validator& nonEmptyPath() {
  static const CLI::Validator check(
      [](std::string& input) -> std::string {
        return input.empty() ? "an empty path (leave the option out for none)" : "";
      },
      "PATH");
  return check;
}

CLI::Validator finiteNumberIn(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& input) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(input, value)) return "'" + input + "' is not a number";
        if (!std::isfinite(value)) return input + " is not a finite number";
        if (value < lo) return fmt::format("{} is below {}", input, lo);
        if (value > hi) return fmt::format("{} is above {}", input, hi);
        return "";
      },
      std::isinf(hi) ? fmt::format("NUMBER >= {}", lo) : fmt::format("NUMBER in [{}, {}]", lo, hi));
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

void checkOutputPath(const std::string& option, const std::string& path) {
  if (path.empty()) return;
  namespace fs = std::filesystem;
  const fs::path file(path);
  const fs::path dir = file.parent_path().empty() ? fs::path(".") : file.parent_path();
  const std::string where = option + " " + path;
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw InputError(where, "its directory " + dir.string() + " does not exist");
  const fs::file_status status = fs::status(file, ec);
  if (fs::is_directory(status) || file.filename().empty())
    throw InputError(where, "is a directory, expected a file name");
  // Outputs are written to a temporary in the directory and renamed (radiosity/atomic_file.h); a
  // device or a pipe is written in place.
  const bool inPlace = fs::exists(status) && !fs::is_regular_file(status);
  if (::access(inPlace ? file.c_str() : dir.c_str(), W_OK) != 0)
    throw InputError(where, fmt::format("cannot write {}: {}", inPlace ? "it" : "its directory",
                                        std::strerror(errno)));
}

void checkDistinctOutputs(std::span<const std::pair<std::string, std::string>> outputs) {
  namespace fs = std::filesystem;
  std::vector<std::pair<fs::path, const std::string*>> seen;
  for (const auto& [option, path] : outputs) {
    if (path.empty()) continue;
    std::error_code ec;
    const fs::path file = fs::weakly_canonical(path, ec);
    for (const auto& [other, otherOption] : seen)
      if (other == file)
        throw InputError(
            option + " " + path,
            fmt::format("is the file {} writes too; give each output its own file", *otherOption));
    seen.emplace_back(file, &option);
  }
}

void checkSolutionOutput(const std::string& path) {
  if (std::filesystem::path(path).extension() != ".rad")
    throw InputError("--save " + path, "expected a .rad file");
  checkOutputPath("--save", path);
}

int statusAfterOutputs(Console& console) {
  if (!InterruptGuard::interrupted()) return 0;
  console.warn("interrupted while the outputs were written; those written are whole");
  return 130;
}

void writeStatsFile(const std::string& path, const Scene& scene, const std::string& sceneName,
                    const std::string& method, double totalSeconds, const Console& console,
                    RunStats& stats) {
  stats.scene = sceneName;
  stats.method = method;
  stats.warnings = console.warnings();
  stats.emittedPower = scene.emittedPower();
  if (!stats.lightGroups.empty()) {
    stats.emittedPower = Color(0.0f);
    for (const RunStats::LightGroupEntry& g : stats.lightGroups) stats.emittedPower += g.power;
  }
  if (!stats.objects.empty())
    stats.absorbedPower = absorbedPower(scene, stats.objects, stats.emissionScales);
  stats.timingsSeconds.total = totalSeconds;
  stats.memoryPeakBytes = peakResidentBytes();
  if (MpiProcesses::split()) {
    // Every rank gets here (each writes its stats; rank 0's alone reach the disk). A rank's
    // busy seconds leave out its sums, where the ranks wait for each other.
    const std::vector<double> busy =
        MpiProcesses::gather(totalSeconds - MpiProcesses::secondsSumming());
    const std::vector<double> summing = MpiProcesses::gather(MpiProcesses::secondsSumming());
    double sum = 0.0, longest = 0.0;
    for (double s : busy) sum += s, longest = std::max(longest, s);
    stats.distributed = {
        {"ranks", MpiProcesses::count()},
        {"busy_seconds_per_rank", busy},
        {"summing_seconds_per_rank", summing},
        {"load_balance", longest > 0.0 ? sum / (double(busy.size()) * longest) : 1.0},
        {"bytes_communicated_rank0", MpiProcesses::bytesCommunicated()}};
  }
  writeRunStats(path, stats);
}

}  // namespace rad::cli
