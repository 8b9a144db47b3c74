// `radiosity bench interior`: a real interior's size (the generated textured atrium, 250k triangles
// at its default detail) rendered by each method with its defaults, each in a process of its own so
// that its peak memory is its own: the time of each stage and the peak resident memory, from the
// child's stats file.
#include <fmt/format.h>
#include <radiosity/radiosity_method.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "bench_workloads.h"
#include "child_process.h"

namespace rad::cli {

nlohmann::json benchInterior(Console& console, int detail) {
  const std::string scene = fmt::format("atrium-textured:{}", detail);
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / fmt::format("radiosity-bench-{}", getpid());
  std::filesystem::create_directories(dir);
  nlohmann::json result = {{"scene", scene}};
  std::string summary = scene + ":";
  for (const RadiosityMethod* m : radiosityMethods()) {
    const std::string method = m->name();
    console.info(fmt::format("bench interior: {} with {}", scene, method));
    const std::string stats = (dir / (method + ".json")).string();
    runToCompletion({selfExecutable(), "render", scene, "--method", method, "--cache-dir", "none",
                     "--quiet", "-o", (dir / (method + ".png")).string(), "--stats", stats});
    const nlohmann::json s = nlohmann::json::parse(std::ifstream(stats));
    const double total = s["timings_s"]["total"].get<double>();
    const double peak = s["memory_peak_bytes"].get<double>();
    result[method] = {
        {"timings_s", s["timings_s"]}, {"memory_peak_bytes", peak}, {"counts", s["counts"]}};
    summary += fmt::format(" {} {:.1f} s / {:.0f} MB,", method, total, peak / 1e6);
  }
  std::filesystem::remove_all(dir);
  summary.pop_back();
  summary += " (each with its defaults, a process of its own)";
  result["summary"] = summary;
  return result;
}

}  // namespace rad::cli
