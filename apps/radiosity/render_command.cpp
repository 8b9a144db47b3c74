// `radiosity render SCENE`: computes light transport with the chosen method and writes an image
// (and, with --stats, the run's numbers).
#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/image.h>
#include <radiosity/radiosity_method.h>
#include <radiosity/surface_radiance.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>

#include "command_support.h"
#include "commands.h"
#include "method_options.h"
#include "picture_options.h"
#include "sensor_options.h"

namespace rad::cli {

namespace {

struct RenderOptions {
  explicit RenderOptions(CLI::App& command) : method(command, {nullptr, "pathtrace", {}, true}) {}
  MethodOptions method;
  double time = 0.0;
  PictureOptions picture;
  SensorOptions sensors;
  std::string scene, output, stats, solution;
  int objectPoints = 64;
};

// Default output name: the scene's stem and the method, e.g. "cornell_pathtrace.png".
std::string defaultOutput(const std::string& scene, const std::string& method) {
  std::string stem = std::filesystem::path(scene).stem().string();
  std::replace(stem.begin(), stem.end(), ':', '-');
  return stem + "_" + method + ".png";
}

// The picture of a method that makes its own (no surface solution: the path tracer).
Image renderPicture(const RadiosityEngine& engine, const Camera& camera, const RenderOptions& o,
                    Console& console, RunStats& stats) {
  const RadiosityMethod& method = engine.method();
  const Scene& scene = engine.scene();
  const RayCaster& caster = engine.caster();
  Stopwatch renderTime;
  RenderedPicture picture =
      method.renderPicture(scene, caster, camera, engine.settings(), console.progress("render"));
  console.finishProgress();
  for (const std::string& w : picture.warnings) console.warn(w);
  if (!picture.resumed.empty()) console.info(picture.resumed);
  stats.timingsSeconds.render = renderTime.seconds();
  stats.counts.rays = picture.rays;
  if (!o.stats.empty() && o.objectPoints > 0) {
    Stopwatch solveTime;
    EstimatedObjects estimated = method.estimateObjects(
        scene, caster, o.objectPoints, engine.settings(), console.progress("surfaces"));
    console.finishProgress();
    stats.objects = std::move(estimated.objects);
    stats.counts.rays += estimated.rays;
    stats.timingsSeconds.solve = solveTime.seconds();
  }
  o.sensors.measure(
      scene,
      [&](std::span<const SensorPoint> points, const SensorSettings& sensors) {
        EstimatedSensors estimated = method.estimateSensors(
            scene, caster, points, sensors, engine.settings(), console.progress("sensors"));
        console.finishProgress();
        stats.counts.rays += estimated.rays;
        return std::move(estimated.irradiance);
      },
      console, stats);
  return std::move(picture.image);
}

// The solution's picture, with the scene's dynamic objects where --time puts them.
Image renderSolution(const RadiosityEngine& engine, const Camera& camera,
                     const SurfaceSolution& solution, const RenderOptions& o, Console& console,
                     RunStats& stats) {
  Stopwatch renderTime;
  o.picture.warnIfDirectUnavailable(solution, o.method.method(), console);
  PictureOptions::warnOfDynamicObjects(engine.scene(), o.method.method(), console);
  Image image = o.picture.render(engine, solution, camera, o.time, console.progress("render"));
  console.finishProgress();
  stats.timingsSeconds.render = renderTime.seconds();
  o.sensors.measure(
      engine.scene(),
      [&](std::span<const SensorPoint> points, const SensorSettings& sensors) {
        std::vector<Color> irradiance =
            engine.sensorIrradiance(solution, o.time, points, sensors, o.picture.objectSettings(),
                                    console.progress("sensors"));
        console.finishProgress();
        return irradiance;
      },
      console, stats);
  return image;
}

// A picture with per-pixel direct light needs the direct light kept apart from the bounces; a
// false-colour one shows the irradiance at each pixel.
MethodSettings solveSettingsFor(const RenderOptions& o) {
  MethodSettings settings = o.method.settings();
  settings.keepDirectLight = o.picture.direct == "per-pixel";
  settings.irradiancePictures = !o.picture.falseColour.empty();
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
  o.sensors.prepare(scene);
  const std::pair<std::string, std::string> outputs[] = {
      {"-o", o.output}, {"--stats", o.stats}, o.sensors.output()};
  checkDistinctOutputs(outputs);

  const Camera camera = o.picture.camera(scene);
  const std::optional<FalseColourScale> falseColour =
      o.picture.falseColour.empty() ? std::nullopt
                                    : std::optional(o.picture.falseColourScale(scene));
  InterruptGuard interruptible;
  // A method that makes its own pictures takes the scene as it is at --time, the objects placed
  // and the groups' emitters scaled: the reference, the objects' light included.
  const bool ownPictures = !o.method.chosen().capabilities().surfaceSolution;
  if (ownPictures && !scene.dynamicObjects.empty()) scene = scene.withDynamicObjectsAt(o.time);
  const StatsReport report{stats, !o.stats.empty()};
  const std::vector<GroupScale>& groups = o.method.groupScales();
  if (ownPictures && !groups.empty())
    scaleEmitters(scene, lightGroupsOf(scene, scene.lights),
                  groupScalesFor(lightGroupsOf(scene, scene.lights), groups));
  const RadiosityEngine engine(scene, solveSettingsFor(o));
  Image image =
      ownPictures
          ? renderPicture(engine, camera, o, console, stats)
          : renderSolution(engine, camera,
                           *solveSurfaces(engine, {groups, o.solution, o.time}, console, report), o,
                           console, stats);
  if (falseColour) image = falseColourPicture(image, *falseColour);
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
  o->picture.addFalseColourTo(*sub);
  o->sensors.addTo(*sub);
  addStatsOption(*sub, o->stats);
  addTimeOption(*sub, o->time);
  sub->add_option("--solution", o->solution,
                  "Render the solution a .rad file keeps (solve --save) instead of solving: its "
                  "method and settings; the scene and its lights at --time must be those it was "
                  "solved for")
      ->check(nonEmptyPath());
  sub->add_option("--object-points", o->objectPoints,
                  "pathtrace: surface points per object for the stats' per-object means (0: skip)")
      ->check(nonNegativeNumber());
  sub->callback(
      [o, &console, &action] { action = [o, &console] { return runRender(*o, console); }; });
}

}  // namespace rad::cli
