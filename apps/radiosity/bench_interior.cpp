// `radiosity bench interior`: a real interior's size (the generated atrium, 250k triangles at its
// default detail) rendered by each method with its defaults, each in a process of its own so
// that its peak memory is its own: the time of each stage and the peak resident memory, from the
// child's stats file.
#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "bench_workloads.h"

extern char** environ;

namespace rad::cli {

namespace {

// Runs this executable with `args`, waiting for it; throws naming the run if it fails.
void runSelf(const std::vector<std::string>& args) {
  const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
  std::vector<char*> argv{const_cast<char*>(self.c_str())};
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, self.c_str(), nullptr, nullptr, argv.data(), environ) != 0)
    throw std::runtime_error("bench interior: cannot start " + self);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error(fmt::format("bench interior: '{} {}' failed", self, args[0]));
}

}  // namespace

nlohmann::json benchInterior(Console& console, int detail) {
  const std::string scene = fmt::format("atrium:{}", detail);
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / fmt::format("radiosity-bench-{}", getpid());
  std::filesystem::create_directories(dir);
  nlohmann::json result = {{"scene", scene}};
  std::string summary = scene + ":";
  for (const std::string method : {"patch", "voxel", "pathtrace"}) {
    console.info(fmt::format("bench interior: {} with {}", scene, method));
    const std::string stats = (dir / (method + ".json")).string();
    runSelf({"render", scene, "--method", method, "--cache-dir", "none", "--quiet", "-o",
             (dir / (method + ".png")).string(), "--stats", stats});
    const nlohmann::json s = nlohmann::json::parse(std::ifstream(stats));
    const double total = s["timings_s"]["total"].get<double>();
    const double peak = s["memory_peak_bytes"].get<double>();
    result[method] = {{"timings_s", s["timings_s"]},
                      {"memory_peak_bytes", peak},
                      {"counts", s["counts"]}};
    summary += fmt::format(" {} {:.1f} s / {:.0f} MB,", method, total, peak / 1e6);
  }
  std::filesystem::remove_all(dir);
  summary.pop_back();
  summary += " (each with its defaults, a process of its own)";
  result["summary"] = summary;
  return result;
}

}  // namespace rad::cli
