// `radiosity animate SCENE`: the scene's light animation as numbered frames, the solution relit
// between frames by its method's relighting (the patch method's Relighter: only the change of the
// lights is shot) instead of solved again; with --video, the frames encoded by ffmpeg.
#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/image.h>
#include <radiosity/radiosity_method.h>
#include <radiosity/surface_radiance.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <numeric>

#include "command_support.h"
#include "commands.h"
#include "frame_files.h"
#include "method_options.h"
#include "picture_options.h"

namespace rad::cli {

namespace {

struct AnimateOptions {
  // The relighter keeps one light state: the groups are scaled in the lights, not solved apart.
  explicit AnimateOptions(CLI::App& command)
      : method(command, {&MethodCapabilities::relight, "patch", {"light_groups"}, true}) {}
  MethodOptions method;
  PictureOptions picture;
  std::string scene, output = "frames/frame_%04d.png", video, stats, solution;
  int frames = 48;
  double fps = 24.0, start = 0.0;
  RelightSettings relight;
};

// The lights at `seconds`, each times its group's scale (--group: the relighter keeps one state
// for all lights, so a group is scaled in the lights it is given).
std::vector<Light> lightsAt(const Scene& scene, double seconds, std::span<const LightGroup> groups,
                            std::span<const Color> scales) {
  return LightState{scene.lightsAt(seconds), {scales.begin(), scales.end()}}.effectiveLights(
      groups);
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// Per frame: its time, the relight's and the render's milliseconds, and what the relight did.
struct FrameRecord {
  double t = 0.0, relightMs = 0.0, renderMs = 0.0;
  RelightStats relight;
};

nlohmann::json framesJson(const std::vector<FrameRecord>& frames) {
  nlohmann::json out = nlohmann::json::array();
  for (const FrameRecord& f : frames)
    out.push_back({{"t", f.t},
                   {"relight_ms", f.relightMs},
                   {"render_ms", f.renderMs},
                   {"patches", f.relight.patches},
                   {"patches_updated", f.relight.patchesUpdated},
                   {"mesh_changed", f.relight.meshChanged},
                   {"rows_computed", f.relight.rowsComputed}});
  return out;
}

int runAnimate(AnimateOptions& o, Console& console) {
  Stopwatch total;
  const FrameFiles frameFiles(o.output);
  if (!o.video.empty()) checkVideoOutput(o.video, frameFiles);
  checkOutputPath("--stats", o.stats);
  const std::pair<std::string, std::string> outputs[] = {{"--video", o.video},
                                                         {"--stats", o.stats}};
  checkDistinctOutputs(outputs);
  RunStats stats;
  Scene scene = loadSceneForCommand(o.scene, o.start, console, stats);
  o.method.resolve(scene, o.solution, console);
  if (!o.solution.empty() && !o.method.groupScales().empty())
    throw InputError("--group",
                     "animate --solution relights the lights the solution was solved "
                     "for; scale light groups when rendering or solving instead");
  const std::vector<LightGroup> groups = lightGroupsOf(scene, scene.lights);
  const std::vector<Color> scales = groupScalesFor(groups, o.method.groupScales());
  scaleEmitters(scene, groups, scales);  // the emitting materials; the lights per frame
  const Camera camera = o.picture.camera(scene);
  frameFiles.createDirectory();

  InterruptGuard interruptible;
  const RadiosityEngine engine(scene, o.method.settings());
  auto timeOf = [&](int frame) { return o.start + double(frame) / o.fps; };
  Stopwatch solveTime;
  const std::vector<Light> first = lightsAt(scene, timeOf(0), groups, scales);
  const std::unique_ptr<Relighting> relighting =
      startRelighting(engine, first, o.solution, o.relight, console);
  Relighting& relighter = *relighting;
  stats.timingsSeconds.solve = solveTime.seconds();

  PictureOptions::warnOfDynamicObjects(scene, o.method.method(), console);
  ProbeCache probes;  // the render's probes, kept while the lights stay and objects barely move
  std::vector<Light> lastLights = scene.lights;
  std::vector<FrameRecord> records;
  const ProgressCallback progress = console.progress("animate");
  int written = 0;
  try {
    for (int f = 0; f < o.frames; ++f) {
      FrameRecord record{timeOf(f), 0.0, 0.0, {}};
      if (f > 0 || !scene.dynamicObjects.empty()) {
        std::vector<Light> lights = lightsAt(scene, record.t, groups, scales);
        if (lights != lastLights) probes.invalidate();
        lastLights = lights;
        record.relight = engine.relight(relighter, lights, record.t);
        record.relightMs = record.relight.milliseconds;
      }
      Stopwatch renderTime;
      const Image image = o.picture.render(engine, relighter.solution(), camera, record.t,
                                           progressPart(progress, f, o.frames), &probes);
      writeImage(frameFiles.name(f), image, o.picture.writeOptions());
      record.renderMs = 1e3 * renderTime.seconds();
      records.push_back(record);
      written = f + 1;
    }
  } catch (const Cancelled&) {
    console.finishProgress();
    console.warn(fmt::format("interrupted: {} of {} frames written, each whole ({}); no video",
                             written, o.frames, o.output));
    return 130;
  }
  console.finishProgress();
  if (const std::string w = relighter.saveCaches(); !w.empty()) console.warn(w);
  if (!o.video.empty()) encodeVideo(frameFiles, o.frames, o.fps, o.video);

  std::vector<double> relightMs, renderMs;
  for (size_t f = 1; f < records.size(); ++f) relightMs.push_back(records[f].relightMs);
  for (const FrameRecord& r : records) renderMs.push_back(r.renderMs);
  if (!o.stats.empty()) {
    stats.counts.patches = relighter.solution().report().patches;
    stats.timingsSeconds.render = std::accumulate(renderMs.begin(), renderMs.end(), 0.0) / 1e3;
    stats.methodDetails = {{"frames", framesJson(records)},
                           {"probe_captures", probes.captures()},
                           {"fps", o.fps},
                           {"ms_per_relight", median(relightMs)},
                           {"ms_per_render", median(renderMs)}};
    stats.settings = settingsOf(o.method.settings());
    writeStatsFile(o.stats, scene, o.scene, o.method.method(), total.seconds(), console, stats);
  }
  console.info(fmt::format(
      "animated {} frames of {} ({}x{}, {:g} fps) in {:.2f} s: {:.1f} ms per relight, {:.1f} ms "
      "per render (medians) -> {}{}",
      o.frames, o.scene, camera.width, camera.height, o.fps, total.seconds(), median(relightMs),
      median(renderMs), o.output, o.video.empty() ? "" : ", video -> " + o.video));
  return 0;
}

}  // namespace

void addAnimateCommand(CLI::App& app, Console& console, CommandAction& action) {
  CLI::App* sub = app.add_subcommand(
      "animate", "Render the scene's light animation, relighting the solution between frames");
  auto o = std::make_shared<AnimateOptions>(*sub);
  addSceneArgument(*sub, o->scene);
  sub->add_option("-o,--output", o->output,
                  "Frame files, numbered by a printf field: %d or %0Nd (default "
                  "frames/frame_%04d.png; .png, .exr or .pfm)");
  sub->add_option("--frames", o->frames, "Frames to render (default 48)")
      ->check(CLI::Range(1, 1000000));
  sub->add_option("--fps", o->fps, "Frames per second of scene time (default 24)")
      ->check(CLI::Range(1e-3, 1e4));
  sub->add_option("--start", o->start, "Scene time of the first frame in seconds (default 0)");
  sub->add_option("--video", o->video,
                  "Also encode the frames (PNG) into a video: .mp4, .mov or .mkv (H.264, by "
                  "ffmpeg, which must be installed)");
  sub->add_option("--solution", o->solution,
                  "Start from the solution a .rad file keeps (solve --save at --start) instead "
                  "of solving")
      ->check(nonEmptyPath());
  sub->add_option("--probe-move-threshold", o->picture.probeMoveThreshold,
                  "Capture a dynamic object's probes again once it moved more than this (scene "
                  "units; default 0: whenever it moved) or the lights changed")
      ->check(nonNegativeNumber());
  sub->add_option("--relight-threshold", o->relight.threshold,
                  "Bring a patch's direct light up to date when it changed by more than this "
                  "fraction of the brightest patch's (default 1e-4)")
      ->check(finiteNumberIn(0.0, 1.0));
  sub->add_option("--relight-tolerance", o->relight.tolerance,
                  "Shoot each change until the unshot power is below this fraction of the light "
                  "put in (default 5e-4)")
      ->check(finiteNumberIn(1e-9, 1.0));
  o->picture.addTo(*sub);
  addStatsOption(*sub, o->stats);
  sub->callback(
      [o, &console, &action] { action = [o, &console] { return runAnimate(*o, console); }; });
}

}  // namespace rad::cli
