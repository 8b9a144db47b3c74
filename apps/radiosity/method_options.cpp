#include "method_options.h"

#include <fmt/format.h>
#include <radiosity/cache_directory.h>
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
#include "mpi_processes.h"

namespace rad::cli {

namespace {

// The light groups, their scales and power, and the per-object means.
void reportObjects(const RadiosityEngine& engine, const SurfaceSolution& solution, double seconds,
                   const StatsReport& report) {
  if (!report.objectMeans) return;
  const Scene& scene = engine.scene();
  report.stats.objects = solution.objectRadiometry();
  if (!scene.dynamicObjects.empty())
    for (const DynamicObjectSummary& s : engine.objectsAt(solution, seconds).summaries())
      report.stats.dynamicObjects.push_back({s.name, s.meanIrradiance, s.lobes});
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

std::vector<std::string> offeredMethods(const MethodUse& use) {
  std::vector<std::string> names = {use.defaultMethod};
  for (const RadiosityMethod* m : radiosityMethods())
    if ((!use.needs || m->capabilities().*use.needs) && m->name() != use.defaultMethod)
      names.push_back(m->name());
  return names;
}

MethodOptions::MethodOptions(CLI::App& c, MethodUse use)
    : use_(std::move(use)), methods_(offeredMethods(use_)) {
  for (const SettingDeclaration& d : solverSettingDeclarations()) {
    const bool read = std::any_of(methods_.begin(), methods_.end(), [&](const std::string& m) {
      return d.readBy(radiosityMethod(m));
    });
    const bool unread =
        std::find(use_.unread.begin(), use_.unread.end(), d.name) != use_.unread.end();
    if (read && !unread && (d.name != "method" || methods_.size() > 1)) addSetting(c, d);
  }
  if (!use_.groupScales) return;
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

void MethodOptions::resolve(const Scene& scene, const std::string& solutionFile, Console& console) {
  if (solutionFile.empty())
    resolve(scene);
  else
    resolveFromSolution(scene, solutionFile, console);
  if (MpiProcesses::rank() == 0) trimCache(console);  // one process keeps the directory
}

void MethodOptions::trimCache(Console& console) const {
  if (settings_.cacheDir.empty()) return;
  const uint64_t removed =
      trimCacheDirectory(settings_.cacheDir, uint64_t(settings_.cacheMaxMegabytes) << 20);
  if (removed > 0)
    console.detail(
        fmt::format("cache {}: removed {:.1f} MB of its least recently used files "
                    "(--cache-max-mb {})",
                    settings_.cacheDir, double(removed) / (1 << 20), settings_.cacheMaxMegabytes));
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
  settings_.processes = MpiProcesses::share();
}

std::unique_ptr<SurfaceSolution> solveSurfaces(const RadiosityEngine& engine,
                                               const SolutionSource& source, Console& console,
                                               const StatsReport& report) {
  const Scene& scene = engine.scene();
  std::string label = engine.model().solveLabel();
  if (!scene.dynamicObjects.empty()) label += ", then with the objects' bounce";
  std::unique_ptr<SurfaceSolution> solution =
      source.file.empty() ? engine.solve(scene.lights, source.seconds, console.progress(label))
                          : engine.load(source.file);
  console.finishProgress();
  const SolveReport r = solution->report();
  for (const std::string& w : r.warnings) console.warn(w);
  if (!r.resumed.empty()) console.info(r.resumed);
  if (!source.groups.empty()) {
    if (solution->lightGroups().empty())
      throw InputError("--group", source.file +
                                      ": its light groups were solved together (solve "
                                      "it with --light-groups to scale them)");
    const std::vector<Color> scales = groupScalesFor(solution->lightGroups(), source.groups);
    solution->setGroupScales(scales);
    if (std::all_of(scales.begin(), scales.end(), [](const Color& s) { return s == Color(0.0f); }))
      console.warn("--group switched every light group off: there is no light");
  }
  RunStats& stats = report.stats;
  stats.methodDetails = nlohmann::json::parse(r.detailsJson);
  stats.counts.patches = r.patches;
  stats.counts.voxels = r.voxels;
  stats.counts.directions = r.directions;
  stats.counts.rays += r.rays;
  stats.timingsSeconds.prepare = r.prepareSeconds;
  stats.timingsSeconds.solve = r.solveSeconds;
  stats.iterations = r.iterations;
  stats.residual = r.residuals.empty() ? 0.0 : r.residuals.back();
  stats.converged = r.converged;
  stats.residuals = r.residuals;
  reportObjects(engine, *solution, source.seconds, report);
  return solution;
}

std::unique_ptr<Relighting> startRelighting(const RadiosityEngine& engine,
                                            std::span<const Light> lights,
                                            const std::string& solutionFile,
                                            const RelightSettings& relight, Console& console,
                                            const std::function<void(double)>& alsoReport) {
  const RadiosityMethod& method = engine.method();
  if (!method.capabilities().relight)
    throw InputError("--method " + method.name(),
                     fmt::format("does not relight (the methods that do: {})",
                                 fmt::join(methodsWith(&MethodCapabilities::relight), ", ")));
  ProgressCallback bar = console.progress(solutionFile.empty() ? engine.model().solveLabel()
                                                               : "reading " + solutionFile);
  const ProgressCallback progress = [bar, alsoReport](double fraction) {
    if (alsoReport) alsoReport(fraction);
    return !bar || bar(fraction);
  };
  std::unique_ptr<Relighting> relighting =
      engine.startRelighting(lights, solutionFile, relight, progress);
  console.finishProgress();
  for (const std::string& w : relighting->solution().report().warnings) console.warn(w);
  return relighting;
}

}  // namespace rad::cli
