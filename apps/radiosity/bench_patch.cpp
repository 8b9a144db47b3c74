// The patch method's throughput: for each workload, form factors by hemisphere ray casting
// (256 rays a patch; no disk cache) and the three solvers to the default tolerance (1e-3).
#include "bench_workloads.h"

#include <fmt/format.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/scene_loader.h>

#include <algorithm>
#include <string>

namespace rad::cli {

namespace {

struct Workload {
  const char* scene;
  size_t patches;
  int rays;
};

nlohmann::json measure(const Workload& w, Console& console) {
  const Scene scene = loadScene(w.scene);
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
    console.detail(fmt::format("bench patch: {} {} patches, {}", w.scene, w.patches, name));
    const PatchRadiosity solution(scene, s);
    const PatchRadiosityStats& p = solution.stats();
    const double total = p.meshSeconds + p.formFactorSeconds + p.solveSeconds;
    solvers[name] = {{"iterations", p.iterations},
                     {"solve_s", p.solveSeconds},
                     {"form_factors_s", p.formFactorSeconds},
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
