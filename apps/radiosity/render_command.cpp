// `radiosity render SCENE`: computes light transport with the chosen method and writes an image
// (and, with --stats, the run's numbers).
#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/image.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/path_tracer.h>
#include <radiosity/surface_radiance.h>
#include <radiosity/voxel_radiosity.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>

#include "command_support.h"
#include "commands.h"
#include "method_options.h"
#include "picture_options.h"

namespace rad::cli {

namespace {

struct RenderOptions {
  explicit RenderOptions(CLI::App& command)
      : method(command, {{"pathtrace", "voxel", "patch"}, {}, true}) {}
  MethodOptions method;
  double time = 0.0;
  PictureOptions picture;
  std::string scene, output, stats, solution;
  int objectPoints = 64;
};

// Default output name: the scene's stem and the method, e.g. "cornell_pathtrace.png".
std::string defaultOutput(const std::string& scene, const std::string& method) {
  std::string stem = std::filesystem::path(scene).stem().string();
  std::replace(stem.begin(), stem.end(), ':', '-');
  return stem + "_" + method + ".png";
}

Image renderWithPathTracer(const Scene& scene, const RayCaster& caster, const Camera& camera,
                           const RenderOptions& o, Console& console, RunStats& stats) {
  Stopwatch renderTime;
  PathTracedImage result =
      renderPathTraced(scene, caster, camera, o.method.pathTracer(), console.progress("render"));
  console.finishProgress();
  for (const std::string& w : result.stats.warnings) console.warn(w);
  if (result.stats.resumedTiles > 0)
    console.info(fmt::format("went on from a checkpoint: {} tiles were done before",
                             result.stats.resumedTiles));
  stats.timingsSeconds.render = renderTime.seconds();
  stats.counts.rays = result.stats.rays;
  if (!o.stats.empty() && o.objectPoints > 0) {
    Stopwatch solveTime;
    PathTracerStats objectStats;
    stats.objects = estimateObjectRadiometry(scene, caster, o.objectPoints, o.method.pathTracer(),
                                             &objectStats, console.progress("surfaces"));
    console.finishProgress();
    stats.counts.rays += objectStats.rays;
    stats.timingsSeconds.solve = solveTime.seconds();
  }
  return std::move(result.image);
}

// The solution's picture, with the scene's dynamic objects where --time puts them.
Image renderSolution(const Scene& scene, const RayCaster& caster, const Camera& camera,
                     const SurfaceSolution& solution, const RenderOptions& o, Console& console,
                     RunStats& stats) {
  Stopwatch renderTime;
  o.picture.warnIfDirectUnavailable(solution, o.method.method(), console);
  PictureOptions::warnOfDynamicObjects(scene, o.method.method(), console);
  Image image = o.picture.render(scene, caster, camera, solution, o.method, o.time,
                                 console.progress("render"));
  console.finishProgress();
  stats.timingsSeconds.render = renderTime.seconds();
  return image;
}

// A voxel picture with per-pixel direct light needs the first shot kept apart from the bounces.
VoxelRadiositySettings voxelSettingsFor(const RenderOptions& o) {
  VoxelRadiositySettings settings = o.method.voxel();
  settings.keepDirectLight = o.picture.direct == "per-pixel";
  return settings;
}

int runRender(RenderOptions& o, Console& console) {
  Stopwatch total;
  RunStats stats;
  Scene scene = loadSceneForCommand(o.scene, o.time, console, stats);
  o.method.resolve(scene, o.solution, console);
  if (o.output.empty()) o.output = defaultOutput(o.scene, o.method.method());
  if (!isSupportedImageFormat(o.output))
    throw InputError("-o " + o.output, "unsupported image format (supported: .png, .exr, .pfm)");
  checkOutputPath("-o", o.output);
  checkOutputPath("--stats", o.stats);

  const Camera camera = o.picture.camera(scene);
  InterruptGuard interruptible;
  // The path tracer takes the objects as they are at --time: the reference, their light included.
  if (o.method.method() == "pathtrace" && !scene.dynamicObjects.empty())
    scene = scene.withDynamicObjectsAt(o.time);
  const RayCaster caster(scene);  // the run's one BVH
  const std::string& method = o.method.method();
  const SolveReport report{stats, !o.stats.empty()};
  const std::vector<GroupScale>& groups = o.method.groupScales();
  if (method == "pathtrace" && !groups.empty())
    scaleEmitters(scene, lightGroupsOf(scene, scene.lights),
                  groupScalesFor(lightGroupsOf(scene, scene.lights), groups));
  const Image image =
      method == "pathtrace" ? renderWithPathTracer(scene, caster, camera, o, console, stats)
      : method == "patch"
          ? renderSolution(scene, caster, camera,
                           solvePatches(scene, caster, o.method.patch(),
                                        {groups, o.solution, o.time}, console, report),
                           o, console, stats)
          : renderSolution(scene, caster, camera,
                           solveVoxels(scene, caster, voxelSettingsFor(o),
                                       {groups, o.solution, o.time}, console, report),
                           o, console, stats);
  InterruptGuard::throwIfInterrupted();
  writeImage(o.output, image, o.picture.writeOptions());
  if (!o.stats.empty()) {
    stats.settings = settingsOf(o.method.settings());
    writeStatsFile(o.stats, scene, o.scene, o.method.method(), total.seconds(), console, stats);
  }
  console.info(fmt::format("rendered {} {}x{} with {} in {:.2f} s -> {}{}", o.scene, camera.width,
                           camera.height, o.method.method(), total.seconds(), o.output,
                           o.stats.empty() ? "" : ", stats -> " + o.stats));
  return statusAfterOutputs(console);
}

}  // namespace

void addRenderCommand(CLI::App& app, Console& console, CommandAction& action) {
  CLI::App* sub = app.add_subcommand("render", "Render an image of a scene");
  auto o = std::make_shared<RenderOptions>(*sub);
  addSceneArgument(*sub, o->scene);
  sub->add_option("-o,--output", o->output,
                  "Output image: .png (tone mapped), .exr or .pfm (linear radiance)");
  o->picture.addTo(*sub);
  addStatsOption(*sub, o->stats);
  addTimeOption(*sub, o->time);
  sub->add_option("--solution", o->solution,
                  "Render the solution a .rad file keeps (solve --save) instead of solving: its "
                  "method and settings; the scene and its lights at --time must be those it was "
                  "solved for");
  sub->add_option("--object-points", o->objectPoints,
                  "pathtrace: surface points per object for the stats' per-object means (0: skip)")
      ->check(nonNegativeNumber());
  sub->callback(
      [o, &console, &action] { action = [o, &console] { return runRender(*o, console); }; });
}

}  // namespace rad::cli
