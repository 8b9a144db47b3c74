// `radiosity solve SCENE --method voxel|patch|...` (the methods that solve the surfaces): computes
// the radiosity solution and exports it (per-element CSV, PLY point cloud, or for the patch method
// the lit mesh as binary glTF) with its numbers in the stats file.
#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/radiosity_method.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>
#include <type_traits>

#include "command_support.h"
#include "commands.h"
#include "method_options.h"
#include "sensor_options.h"

namespace rad::cli {

namespace {

struct SolveOptions {
  // No pictures: no samples per pixel.
  explicit SolveOptions(CLI::App& command)
      : method(command, {&MethodCapabilities::surfaceSolution, "voxel", {"spp"}, true}) {}
  MethodOptions method;
  SensorOptions sensors;
  double time = 0.0;
  float exposure = 0.0f;
  int lightmap = 0;  ///< texels a side of the .glb's lightmap atlas; 0: vertex colours
  std::string scene, exportPath, stats, save;
};

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

// The lit mesh as glTF; with dynamic objects, theirs too (placed at --time, a node each). With
// a lightmap, the scene's triangles under their atlas (a lightmap holds static light only).
void exportGlbWithObjects(const SolveOptions& o, const RadiosityEngine& engine,
                          const SurfaceSolution& solution, Console& console) {
  const Scene& scene = engine.scene();
  if (o.lightmap > 0) {
    if (!scene.dynamicObjects.empty())
      console.warn(
          fmt::format("--lightmap: dynamic objects ({}) are left out of {} (they move; "
                      "a lightmap holds the static scene's light)",
                      scene.dynamicObjects.size(), o.exportPath));
    return solution.exportLightmappedGlb(o.exportPath, o.lightmap, o.exposure);
  }
  engine.exportGlb(solution, o.time, o.exportPath, o.exposure);
}

// Exports the solution, writes the stats and prints the summary line.
int finishSolve(const SolveOptions& o, const RadiosityEngine& engine,
                const SurfaceSolution& solution, const std::string& ext, const Stopwatch& total,
                RunStats& stats, Console& console) {
  const Scene& scene = engine.scene();
  InterruptGuard::throwIfInterrupted();
  if (ext == ".csv") solution.exportCsv(o.exportPath);
  if (ext == ".ply") solution.exportPly(o.exportPath, o.exposure);
  if (ext == ".glb") exportGlbWithObjects(o, engine, solution, console);
  if (!o.save.empty()) solution.save(o.save, solvedWith(o.method.settings()));
  o.sensors.measure(
      scene,
      [&](std::span<const SensorPoint> points, const SensorSettings& sensors) {
        std::vector<Color> irradiance = engine.sensorIrradiance(solution, o.time, points, sensors,
                                                                {}, console.progress("sensors"));
        console.finishProgress();
        return irradiance;
      },
      console, stats);
  if (!o.stats.empty()) {
    stats.settings = settingsOf(o.method.settings());
    writeStatsFile(o.stats, scene, o.scene, o.method.method(), total.seconds(), console, stats);
  }
  console.info(fmt::format("solved {} with {}: {}, {:.2f} s{}{}{}{}", o.scene, o.method.method(),
                           solution.report().summary, total.seconds(),
                           o.exportPath.empty() ? "" : " -> " + o.exportPath,
                           o.lightmap > 0 ? " + " + lightmapIrradiancePath(o.exportPath) : "",
                           o.save.empty() ? "" : ", solution -> " + o.save,
                           o.stats.empty() ? "" : ", stats -> " + o.stats));
  return statusAfterOutputs(console);
}

int runSolve(SolveOptions& o, Console& console) {
  Stopwatch total;
  const std::string ext = o.exportPath.empty() ? "" : lowerExtension(o.exportPath);
  if (!o.exportPath.empty() && ext != ".csv" && ext != ".ply" && ext != ".glb")
    throw InputError("--export " + o.exportPath,
                     "unsupported export format (supported: .csv, .ply, .glb)");
  if (!o.save.empty()) checkSolutionOutput(o.save);
  checkOutputPath("--export", o.exportPath);
  checkOutputPath("--stats", o.stats);
  if (o.lightmap > 0 && ext != ".glb")
    throw InputError("--lightmap", "a lightmap atlas goes with a .glb export (--export FILE.glb)");
  if (o.lightmap > 0) checkOutputPath("--lightmap", lightmapIrradiancePath(o.exportPath));
  const std::pair<std::string, std::string> outputs[] = {
      {"--export", o.exportPath},
      {"--stats", o.stats},
      {"--save", o.save},
      {"--lightmap", o.lightmap > 0 ? lightmapIrradiancePath(o.exportPath) : ""},
      o.sensors.output()};
  checkDistinctOutputs(outputs);
  RunStats stats;
  Scene scene = loadSceneForCommand(o.scene, o.time, console, stats);
  o.sensors.prepare(scene);
  // Before the solve: an atlas too small for the scene's charts is refused before any work.
  if (o.lightmap > 0) requireLightmapExport(scene, o.lightmap);
  o.method.resolve(scene, "", console);
  if (!o.save.empty() && !o.method.chosen().capabilities().saveSolution)
    throw InputError(
        "--save",
        fmt::format("the {} method keeps no solution files (those that do: {})", o.method.method(),
                    fmt::join(methodsWith(&MethodCapabilities::saveSolution), ", ")));
  InterruptGuard interruptible;
  const StatsReport report{stats, !o.stats.empty()};
  // A saved solution keeps its direct light apart, for pictures with per-pixel direct light.
  MethodSettings settings = o.method.settings();
  if (!o.save.empty()) settings.keepDirectLight = true;
  const RadiosityEngine engine(scene, settings);
  const std::unique_ptr<SurfaceSolution> solution =
      solveSurfaces(engine, {o.method.groupScales(), "", o.time}, console, report);
  return finishSolve(o, engine, *solution, ext, total, stats, console);
}

}  // namespace

void addSolveCommand(CLI::App& app, Console& console, CommandAction& action) {
  CLI::App* sub = app.add_subcommand("solve", "Compute a radiosity solution and export it");
  auto o = std::make_shared<SolveOptions>(*sub);
  addSceneArgument(*sub, o->scene);
  sub->add_option("--export", o->exportPath,
                  "Per-element results: .csv (a row per voxel side or patch), .ply (a point cloud) "
                  "or .glb (the lit mesh, vertex colours = radiance: the patches, or with --method "
                  "voxel the scene's triangles cut to the voxel size)");
  sub->add_option(
         "--exposure", o->exposure,
         "Vertex colours of a .glb or .ply export: radiance x 2^EV before they are clamped "
         "to [0, 1] (the .glb says which in its extras)")
      ->check(finiteNumberIn(-64.0, 64.0));
  sub->add_option("--save", o->save,
                  "Save the solution (.rad) for render, animate and serve --solution: no solve "
                  "again; its light groups too (--light-groups)");
  sub->add_option("--lightmap", o->lightmap,
                  "With a .glb export: the scene's own triangles under a lightmap atlas of SIZE x "
                  "SIZE texels (TEXCOORD_1; the radiance shown, x 2^exposure), and beside the "
                  ".glb the irradiance atlas as EXR (FILE.lightmap.exr) for engines")
      ->check(CLI::Range(16, 16384));
  o->sensors.addTo(*sub);
  addStatsOption(*sub, o->stats);
  addTimeOption(*sub, o->time);
  sub->callback(
      [o, &console, &action] { action = [o, &console] { return runSolve(*o, console); }; });
}

}  // namespace rad::cli
