#include "method_options.h"

#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/solution_file.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "command_support.h"
#include "core/cache_directory.h"
#include "lighting/dynamic_objects.h"
#include "mpi_processes.h"

namespace rad::cli {

namespace {

// Solves with a progress bar, then prints the method's warnings (settings that lose light, a
// cache file that could not be used).
template <class Model, class Settings>
auto solveShowingProgress(const Scene& scene, const RayCaster& caster, const Settings& settings,
                          const SolutionSource& source, const std::string& label,
                          Console& console) {
  const Model model(scene, caster, settings);
  auto solution = source.file.empty() ? model.solve(scene.lights, console.progress(label))
                                      : model.load(source.file, scene.lights);
  console.finishProgress();
  if (!scene.dynamicObjects.empty() && source.file.empty()) {
    // Once more with the objects in place: their reflected light as lights, and their shadows
    // in the lights' direct light.
    const Scene placed = scene.withDynamicObjectsAt(source.seconds);
    const RayCaster placedCaster(placed);
    std::vector<Light> lights = scene.lights;
    for (const Light& l :
         DynamicObjectLighting(placed, solution, caster, placedCaster).objectLights())
      lights.push_back(l);
    const ProgressCallback progress = console.progress(label + ", objects' bounce");
    solution = model.solve(lights, placedCaster, progress);
    console.finishProgress();
  }
  for (const std::string& w : solution.stats().warnings) console.warn(w);
  if (source.groups.empty()) return solution;
  if (solution.lightGroups().empty())
    throw InputError("--group", source.file +
                                    ": its light groups were solved together (solve "
                                    "it with --light-groups to scale them)");
  const std::vector<Color> scales = groupScalesFor(solution.lightGroups(), source.groups);
  solution.setGroupScales(scales);
  if (std::all_of(scales.begin(), scales.end(), [](const Color& s) { return s == Color(0.0f); }))
    console.warn("--group switched every light group off: there is no light");
  return solution;
}

// The light groups, their scales and power, and the per-object means.
void reportObjects(const Scene& scene, const RayCaster& caster, const SurfaceSolution& solution,
                   double seconds, const SolveReport& report) {
  if (!report.objectMeans) return;
  report.stats.objects = solution.objectRadiometry();
  if (!scene.dynamicObjects.empty()) {
    const Scene placed = scene.withDynamicObjectsAt(seconds);
    const RayCaster placedCaster(placed);
    for (const auto& s : DynamicObjectLighting(placed, solution, caster, placedCaster).summaries())
      report.stats.dynamicObjects.push_back({s.name, s.meanIrradiance, s.lobes});
  }
  const std::span<const LightGroup> groups = solution.lightGroups();
  for (size_t g = 0; g < groups.size(); ++g) {
    const Color scale = solution.groupScales()[g];
    report.stats.lightGroups.push_back(
        {groups[g].name, scale, scale * groupPower(scene, scene.lights, groups[g])});
  }
  const std::span<const Color> scales = solution.emissionScales();
  report.stats.emissionScales.assign(scales.begin(), scales.end());
}

// The declaration's own check, so that a flag's message is the scene key's.
CLI::Validator checkOf(const SettingDeclaration& d) {
  return CLI::Validator(
      [&d](std::string& input) -> std::string {
        std::string why;
        d.parse(input, why);
        return why;
      },
      "");
}

}  // namespace

MethodOptions::MethodOptions(CLI::App& c, MethodUse use) : methods_(std::move(use.methods)) {
  for (const SettingDeclaration& d : solverSettingDeclarations()) {
    const bool read = std::any_of(methods_.begin(), methods_.end(),
                                  [&](const std::string& m) { return d.readBy(m); });
    const bool unread = std::find(use.unread.begin(), use.unread.end(), d.name) != use.unread.end();
    if (read && !unread && (d.name != "method" || methods_.size() > 1)) addSetting(c, d);
  }
  if (!use.groupScales) return;
  c.add_option("--group", groupText_,
               "Scale a light group's light, NAME=SCALE or NAME=r,g,b (0: off; repeatable); "
               "solves the groups apart (--light-groups). A light's group is its \"group\", "
               "else light<i>; an emitting material's, its name")
      ->type_name("NAME=SCALE");
}

void MethodOptions::addSetting(CLI::App& c, const SettingDeclaration& d) {
  if (d.name == "method") {
    options_[d.name] = c.add_option("--method", text_[d.name],
                                    fmt::format("{} (default: {})", d.help, methods_.front()))
                           ->check(CLI::IsMember(methods_));
  } else if (d.type == SettingType::Flag) {
    const std::string flag = d.flag();
    options_[d.name] =
        c.add_flag(flag + ",!--no-" + flag.substr(2), switches_[d.name], d.fullHelp())
            ->group(d.group);
  } else {
    const char* type = d.type == SettingType::Integer  ? "INT"
                       : d.type == SettingType::Number ? "NUMBER"
                       : d.type == SettingType::Choice ? "NAME"
                                                       : "TEXT";
    options_[d.name] =
        c.add_option(d.flag(), text_[d.name], d.fullHelp())->check(checkOf(d))->type_name(type);
    if (d.group != "General") options_[d.name]->group(d.group);
  }
}

SolverSettings MethodOptions::given() const {
  SolverSettings given;
  for (const SettingDeclaration& d : solverSettingDeclarations()) {
    if (!options_.contains(d.name) || !*options_.at(d.name)) continue;
    if (d.type == SettingType::Flag) {
      given.values[d.name] = switches_.at(d.name);
      continue;
    }
    std::string why;
    const std::optional<SettingValue> v = d.parse(text_.at(d.name), why);
    if (!v) throw InputError(d.flag(), why);  // checked by CLI11 already
    given.values[d.name] = *v;
  }
  return given;
}

void MethodOptions::parseGroups(const Scene& scene) {
  groupScales_.clear();
  for (const std::string& text : groupText_) groupScales_.push_back(parseGroupScale(text));
  groupScalesFor(lightGroupsOf(scene, scene.lights), groupScales_);  // every name a group's
}

void MethodOptions::resolveFromSolution(const Scene& scene, const std::string& path,
                                        Console& console) {
  parseGroups(scene);
  SolutionFileInfo file = readSolutionFileInfo(path);
  SolverSettings run;  // the run's own: where the cache is, how pictures sample
  for (const auto& [name, value] : given().values) {
    if (name == "cache_dir" || name == "cache_max_mb" || name == "spp" || name == "seed")
      run.values[name] = value;
    else if (name != "method" || std::get<std::string>(value) != file.method)
      console.warn(fmt::format("{} ignored: the solution in {} was solved with its own settings",
                               findSolverSetting(name)->flag(), path));
  }
  file.settings.values.erase("cache_dir");
  file.settings.values.erase("cache_max_mb");
  file.settings.values["method"] = file.method;
  settings_ = resolveMethodSettings(file.settings, run, path);
  if (std::find(methods_.begin(), methods_.end(), settings_.method) == methods_.end())
    throw InputError(path, fmt::format("a {} solution; this command takes {}", settings_.method,
                                       fmt::join(methods_, ", ")));
}

Relighter startRelighter(const PatchModel& model, std::span<const Light> lights,
                         const std::string& solutionFile, const RelightSettings& settings,
                         Console& console, const std::function<void(double)>& alsoReport) {
  auto reported = [&](const std::string& label) -> ProgressCallback {
    ProgressCallback bar = console.progress(label);
    return [bar, alsoReport](double fraction) {
      if (alsoReport) alsoReport(fraction);
      return !bar || bar(fraction);
    };
  };
  Relighter relighter =
      solutionFile.empty()
          ? Relighter(model, lights, settings, reported("patch solve"))
          : Relighter(model, model.load(solutionFile, lights), settings, reported("form factors"));
  console.finishProgress();
  for (const std::string& w : relighter.solution().stats().warnings) console.warn(w);
  return relighter;
}

void MethodOptions::resolve(const Scene& scene, const std::string& solutionFile, Console& console) {
  if (solutionFile.empty())
    resolve(scene);
  else
    resolveFromSolution(scene, solutionFile, console);
  if (MpiProcesses::rank() == 0) trimCache(console);  // one process keeps the directory
}

void MethodOptions::trimCache(Console& console) const {
  if (settings_.patch.cacheDir.empty()) return;
  const uint64_t removed =
      trimCacheDirectory(settings_.patch.cacheDir, uint64_t(settings_.cacheMaxMegabytes) << 20);
  if (removed > 0)
    console.detail(fmt::format(
        "cache {}: removed {:.1f} MB of its least recently used files "
        "(--cache-max-mb {})",
        settings_.patch.cacheDir, double(removed) / (1 << 20), settings_.cacheMaxMegabytes));
}

SolverSettings solvedWith(const MethodSettings& settings) {
  SolverSettings out;
  // Not a value that stands for "unset" (patch_size 0: from the patch count), which the
  // settings' own check refuses: the default gives it back.
  for (auto& [name, value] : settingsOf(settings))
    if (findSolverSetting(name)->problem(value).empty()) out.values[name] = value;
  return out;
}

void MethodOptions::resolve(const Scene& scene) {
  SolverSettings given = this->given();
  parseGroups(scene);
  if (!groupScales_.empty()) given.values["light_groups"] = true;
  if (!given.values.contains("method") && !scene.solver.values.contains("method"))
    given.values["method"] = methods_.front();
  settings_ = resolveMethodSettings(scene.solver, given, scene.name);
  if (std::find(methods_.begin(), methods_.end(), settings_.method) == methods_.end())
    throw InputError(scene.name + ": /solver/method",
                     fmt::format("method '{}' is not available here (available: {})",
                                 settings_.method, fmt::join(methods_, ", ")));
  settings_.pathTracer.processes = MpiProcesses::share();
  settings_.voxel.processes = MpiProcesses::share();
  settings_.patch.processes = MpiProcesses::share();
}

VoxelRadiosity solveVoxels(const Scene& scene, const RayCaster& caster,
                           const VoxelRadiositySettings& settings, const SolutionSource& source,
                           Console& console, const SolveReport& report) {
  // The label says what ends the solve, so that the time left reads against it.
  const std::string label =
      settings.tolerance > 0.0
          ? fmt::format("voxel solve (to {:g} of the light still bouncing, {} iterations at most)",
                        settings.tolerance, settings.iterations)
          : fmt::format("voxel solve ({} iterations)", settings.iterations);
  VoxelRadiosity solution =
      solveShowingProgress<VoxelModel>(scene, caster, settings, source, label, console);
  RunStats& stats = report.stats;
  const VoxelRadiosityStats& v = solution.stats();
  if (v.resumedIterations > 0)
    console.info(fmt::format("went on from a checkpoint: {} iteration{} were done before",
                             v.resumedIterations, v.resumedIterations == 1 ? "" : "s"));
  stats.methodDetails = {
      {"resumed_iterations", v.resumedIterations},
      {"voxel_size", v.voxelSize},
      {"cells", v.voxels},
      {"sides", v.sides},
      {"visits", v.visits},
      {"visits_per_s", double(v.visits) / std::max(v.sweepSeconds, 1e-9)},
      {"shadow_rays", v.shadowRays},
      {"sweep_threads", v.sweepThreads},
      {"tail_share", v.tailShare},
      {"later_directions", v.laterDirections},
      {"memory_bytes", v.memoryBytes},
      {"bytes_per_side", double(v.memoryBytes) / double(std::max<size_t>(v.sides, 1))},
      {"bytes_per_voxel", double(v.memoryBytes) / double(std::max<size_t>(v.voxels, 1))},
      {"seconds",
       {{"voxelize", v.voxelizeSeconds},
        {"first_shot", v.directSeconds},
        {"sweeps", v.sweepSeconds},
        {"iterations", v.iterationSeconds}}}};
  stats.counts.voxels = v.sides;
  stats.counts.directions = v.directions;
  stats.counts.rays += v.shadowRays;
  stats.timingsSeconds.prepare = v.voxelizeSeconds;
  stats.timingsSeconds.solve = v.directSeconds + v.sweepSeconds;
  stats.iterations = int(v.residuals.size());
  stats.residual = v.residuals.empty() ? 0.0 : v.residuals.back();
  stats.converged = v.converged;
  stats.residuals = v.residuals;
  reportObjects(scene, caster, solution, source.seconds, report);
  return solution;
}

PatchRadiosity solvePatches(const Scene& scene, const RayCaster& caster,
                            const PatchRadiositySettings& settings, const SolutionSource& source,
                            Console& console, const SolveReport& report) {
  PatchRadiosity solution =
      solveShowingProgress<PatchModel>(scene, caster, settings, source, "patch solve", console);
  RunStats& stats = report.stats;
  const PatchRadiosityStats& p = solution.stats();
  stats.methodDetails = {
      {"patch_size", p.patchSize},
      {"nodes", p.nodes},
      {"vertices", p.vertices},
      {"table_entries", p.nonZeros},
      {"exact_columns", p.exactColumns},
      {"table_bytes", p.tableBytes},
      {"dropped_entry_fraction", p.droppedEntryFraction},
      {"dropped_sum_fraction", p.droppedSumFraction},
      {"dropped_worst_row_fraction", p.droppedWorstRowFraction},
      {"rows_dropping_over_1_percent", p.rowsDroppingOverOnePercent},
      {"row_sum",
       {{"min", p.rowSumMin},
        {"mean", p.rowSumMean},
        {"max", p.rowSumMax},
        {"estimated_max", p.rowSumEstimatedMax},
        {"rows_scaled", p.rowsScaledToClosure},
        {"reflected_share_max", p.reflectedShareMax},
        {"scaled_for_reflection", p.scaledForReflection}}},
      {"cache_loaded", p.cacheLoaded},
      {"cache_file", p.cacheFile},
      {"solver", p.solver},
      {"diverging", p.diverging},
      {"shots", p.shots},
      {"rays_per_s", double(p.rays - p.lightRays) / std::max(p.formFactorSeconds, 1e-9)},
      {"light_rays", p.lightRays},
      {"rows_computed", p.rowsComputed},
      {"rows_reused", p.rowsReused},
      {"master_rows", p.masterRows},
      {"base_patches", p.basePatches},
      {"refined_splits", p.refinedSplits},
      {"refine_rounds", p.refineRounds},
      {"light_rays_per_s", double(p.lightRays) / std::max(p.lightSeconds, 1e-9)},
      {"memory_bytes", p.memoryBytes},
      {"seconds",
       {{"mesh", p.meshSeconds},
        {"form_factors", p.formFactorSeconds},
        {"cache_load", p.cacheLoadSeconds},
        {"light", p.lightSeconds},
        {"solve", p.solveSeconds}}}};
  stats.counts.patches = p.patches;
  stats.counts.rays += p.rays;
  stats.timingsSeconds.prepare = p.meshSeconds + p.formFactorSeconds + p.cacheLoadSeconds;
  stats.timingsSeconds.solve = p.lightSeconds + p.solveSeconds;
  stats.iterations = p.iterations;
  stats.residual = p.residuals.empty() ? 0.0 : p.residuals.back();
  stats.converged = p.converged;
  stats.residuals = p.residuals;
  reportObjects(scene, caster, solution, source.seconds, report);
  return solution;
}

}  // namespace rad::cli
