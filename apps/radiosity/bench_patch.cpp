// The patch method's throughput: for each workload, form factors by hemisphere ray casting
// (256 rays a patch) and the three solvers to the default tolerance (1e-3). Gauss-Seidel and
// Jacobi solve the same table: the Gauss-Seidel run computes it and leaves it in a scratch
// form-factor cache that the Jacobi run loads, so its rays are cast once (progressive refinement
// casts the rows it asks for itself, without a cache).
#include "bench_workloads.h"

#include <radiosity/patch_radiosity.h>
#include <radiosity/scene_loader.h>

#include <fmt/format.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <system_error>

namespace rad::cli {

namespace {

struct Workload {
  const char* scene;
  size_t patches;
  int rays;
};

// An empty directory of its own under the system's temporary one, removed with the object.
class ScratchDirectory {
 public:
  explicit ScratchDirectory(const std::string& name)
      : path_(std::filesystem::temp_directory_path() / fmt::format("{}-{}", name, ::getpid())) {
    std::filesystem::remove_all(path_);  // a table left by a killed run must not be loaded
  }
  ~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

nlohmann::json measure(const Workload& w, Console& console) {
  const Scene scene = loadScene(w.scene);
  const ScratchDirectory tableCache("radiosity-bench-patch");
  double tableSeconds = 0.0;  // the shared table's computation, by the run that cast its rays
  nlohmann::json solvers = nlohmann::json::object();
  nlohmann::json result;
  std::string fastest;
  double fastestTotal = 1e300;
  for (auto [name, kind] : {std::pair{"gauss-seidel", PatchSolverKind::GaussSeidel},
                            {"jacobi", PatchSolverKind::Jacobi},
                            {"progressive", PatchSolverKind::Progressive}}) {
    PatchRadiositySettings s;
    s.targetPatches = w.patches;
    s.formFactorRays = w.rays;
    s.solver = kind;
    if (kind != PatchSolverKind::Progressive) s.cacheDir = tableCache.path().string();
    console.detail(fmt::format("bench patch: {} {} patches, {}", w.scene, w.patches, name));
    const PatchRadiosity solution(scene, s);
    const PatchRadiosityStats& p = solution.stats();
    // A cache that cannot be written only costs Jacobi its own table.
    for (const std::string& warning : p.warnings) console.warn(warning);
    if (kind == PatchSolverKind::GaussSeidel) tableSeconds = p.formFactorSeconds;
    const double formFactorSeconds = p.cacheLoaded ? tableSeconds : p.formFactorSeconds;
    const double total = p.meshSeconds + formFactorSeconds + p.solveSeconds;
    solvers[name] = {{"iterations", p.iterations},
                     {"solve_s", p.solveSeconds},
                     {"form_factors_s", formFactorSeconds},
                     {"total_s", total},
                     {"residual", p.residuals.empty() ? 0.0 : p.residuals.back()},
                     {"table_bytes", p.tableBytes}};
    if (total < fastestTotal) fastestTotal = total, fastest = name;
    if (kind != PatchSolverKind::GaussSeidel) continue;
    result = {{"scene", w.scene},
              {"patches", p.patches},
              {"rays_per_patch", w.rays},
              {"mesh_s", p.meshSeconds},
              {"form_factors_s", p.formFactorSeconds},
              {"rays_per_s", double(p.rays) / std::max(p.formFactorSeconds, 1e-9)},
              {"table_entries", p.nonZeros},
              {"table_bytes", p.tableBytes},
              {"row_sum_mean", p.rowSumMean}};
  }
  result["solvers"] = solvers;
  result["fastest_solver"] = fastest;
  const auto& gs = solvers["gauss-seidel"];
  result["summary"] = fmt::format(
      "{} {} patches: {:.1f} M rays/s, table {:.0f} MB, form factors + solve {:.2f} s "
      "(gauss-seidel {:.3f} s, jacobi {:.3f} s, progressive {:.2f} s incl. lazy rows; fastest {})",
      w.scene, result["patches"].get<size_t>(), result["rays_per_s"].get<double>() * 1e-6,
      double(result["table_bytes"].get<size_t>()) / 1e6, gs["total_s"].get<double>(),
      gs["solve_s"].get<double>(), solvers["jacobi"]["solve_s"].get<double>(),
      solvers["progressive"]["total_s"].get<double>(), fastest);
  return result;
}

}  // namespace

nlohmann::json benchPatch(Console& console) {
  nlohmann::json runs = nlohmann::json::array();
  std::string summary;
  for (const Workload& w : {Workload{"cornell", 10000, 256}, Workload{"room:4", 10000, 256},
                            Workload{"cornell", 100000, 128}}) {
    runs.push_back(measure(w, console));
    summary += (summary.empty() ? "" : "; ") + runs.back()["summary"].get<std::string>();
  }
  return {{"workloads", runs}, {"summary", summary}};
}

}  // namespace rad::cli
