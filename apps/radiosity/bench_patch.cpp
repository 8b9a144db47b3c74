// The patch method's throughput: for each workload, form factors by hemisphere ray casting
// (256 rays a patch) and the three solvers to the default tolerance (1e-3). Gauss-Seidel and
// Jacobi solve the same table: the Gauss-Seidel run computes it and leaves it in a scratch
// form-factor cache that the Jacobi run loads, so its rays are cast once (progressive refinement
// casts the rows it asks for itself, without a cache).
#include <fmt/format.h>
#include <radiosity/kernel_timing.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/ray_caster.h>
#include <radiosity/scene_loader.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string>
#include <system_error>

#include "bench_workloads.h"

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
              {"rays_per_s", double(p.rays - p.lightRays) / std::max(p.formFactorSeconds, 1e-9)},
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

// cornell-spot: the lights' direct light, adaptive subdivision and the solve on the refined mesh;
// then the spot moved 10 cm on the same model (what a solve of the model pays for moved lights,
// without the Relighter's shooting of the change: the rows of the nodes the new beam edge made,
// the table, the solve).
nlohmann::json measureLights(Console& console) {
  const Scene scene = loadScene("cornell-spot");
  console.detail("bench patch: cornell-spot, adaptive subdivision");
  PatchRadiositySettings s;
  s.cacheDir.clear();
  const RayCaster caster(scene);
  const PatchModel model(scene, caster, s);
  const PatchRadiosity solution = model.solve(scene.lights);
  const PatchRadiosityStats& p = solution.stats();
  std::vector<Light> moved = scene.lights;
  moved[0].position.x += 100.0f;
  const auto start = std::chrono::steady_clock::now();
  const PatchRadiosity again = model.solve(moved);
  const double movedSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const DirectLightPassTiming pass = measurePatchDirectLight(scene, 10000, 4);
  const double total = p.meshSeconds + p.lightSeconds + p.formFactorSeconds + p.solveSeconds;
  nlohmann::json result = {
      {"scene", "cornell-spot"},
      {"base_patches", p.basePatches},
      {"patches", p.patches},
      {"refined_splits", p.refinedSplits},
      {"refine_rounds", p.refineRounds},
      {"rows_computed", p.rowsComputed},
      {"light_rays", p.lightRays},
      {"light_s", p.lightSeconds},
      {"light_rays_per_s", double(p.lightRays) / std::max(p.lightSeconds, 1e-9)},
      {"table_entries", p.nonZeros},
      {"form_factors_s", p.formFactorSeconds},
      {"total_s", total},
      {"moved_rows_computed", again.stats().rowsComputed},
      {"moved_rows_reused", again.stats().rowsReused},
      {"moved_s", movedSeconds},
      {"direct_pass_patches", pass.patches},
      {"direct_pass_ms", pass.medianMs}};
  result["summary"] = fmt::format(
      "cornell-spot: {} -> {} patches by adaptive subdivision ({} rounds), {} rows, light rays "
      "{:.1f} M/s, {} table entries, {:.2f} s in all; spot moved 10 cm: {} rows cast, {} reused, "
      "{:.2f} s; direct light of {} patches x 4 points {:.2f} ms",
      p.basePatches, p.patches, p.refineRounds, p.rowsComputed,
      result["light_rays_per_s"].get<double>() * 1e-6, p.nonZeros, total,
      again.stats().rowsComputed, again.stats().rowsReused, movedSeconds, pass.patches,
      pass.medianMs);
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
  runs.push_back(measureLights(console));
  summary += "; " + runs.back()["summary"].get<std::string>();
  return {{"workloads", runs}, {"summary", summary}};
}

}  // namespace rad::cli
