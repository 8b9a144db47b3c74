// `radiosity render SCENE`: computes light transport with the chosen method and writes an image
// (and, with --stats, the run's numbers).
#include "commands.h"

#include "core/memory_usage.h"
#include "output/run_stats.h"

#include <radiosity/error.h>
#include <radiosity/image.h>
#include <radiosity/path_tracer.h>
#include <radiosity/scene_loader.h>

#include <CLI/CLI.hpp>
#include <glm/gtc/constants.hpp>
#include <fmt/format.h>

#include <filesystem>
#include <memory>

namespace rad::cli {

namespace {

struct RenderOptions {
  std::string scene;
  std::string output;
  std::string method = "pathtrace";
  int width = 0, height = 0;
  int spp = 64;
  int maxDepth = 256;
  uint64_t seed = 1;
  float exposure = 0.0f;
  bool exrFloat = false;
  std::string stats;
  int objectPoints = 64;
  CLI::Option *methodFlag, *sppFlag, *seedFlag, *maxDepthFlag, *outputFlag;
};

// Default output name: the scene's stem and the method, e.g. "cornell_pathtrace.png".
std::string defaultOutput(const std::string& scene, const std::string& method) {
  std::string stem = std::filesystem::path(scene).stem().string();
  for (char& c : stem)
    if (c == ':') c = '-';
  return stem + "_" + method + ".png";
}

// The flag wins over the scene's "solver" object, which wins over the default.
void applySceneSolverSettings(RenderOptions& o, const Scene& scene) {
  const SolverSettings& s = scene.solver;
  if (!*o.methodFlag && s.method) o.method = *s.method;
  if (!*o.sppFlag && s.spp) o.spp = *s.spp;
  if (!*o.seedFlag && s.seed) o.seed = *s.seed;
  if (!*o.maxDepthFlag && s.maxDepth) o.maxDepth = *s.maxDepth;
  if (o.method != "pathtrace")
    throw InputError(scene.name, fmt::format("method '{}' is not available in this build (available: "
                                             "pathtrace)", o.method));
}

Color absorbedPower(const Scene& scene, const std::vector<ObjectRadiometry>& objects) {
  // Per object: absorbed = (H - (B - E)) A = H A - rho H A; B - E = rho H, so use H and B.
  Color absorbed(0.0f);
  std::vector<Color> emitted(scene.objects.size(), Color(0.0f));
  std::vector<double> area(scene.objects.size(), 0.0);
  for (const Face& f : scene.faces) {
    emitted[f.object] += scene.materials[f.material].emission * (glm::pi<float>() * f.area);
    area[f.object] += f.area;
  }
  for (size_t i = 0; i < objects.size() && i < scene.objects.size(); ++i) {
    const ObjectRadiometry& o = objects[i];
    const Color reflected = o.meanRadiosity * float(o.area) - emitted[i];
    absorbed += o.meanIrradiance * float(o.area) - reflected;
  }
  return absorbed;
}

int runRender(RenderOptions& o, Console& console) {
  Stopwatch total;
  if (o.output.empty()) o.output = defaultOutput(o.scene, o.method);
  if (!isSupportedImageFormat(o.output))
    throw InputError("-o " + o.output, "unsupported image format (supported: .png, .exr, .pfm)");

  RunStats stats;
  Stopwatch loadTime;
  Scene scene = loadScene(o.scene);
  stats.timingsSeconds.load = loadTime.seconds();
  for (const std::string& w : scene.warnings) console.warn(scene.name + ": " + w);
  requireEmitters(scene);
  applySceneSolverSettings(o, scene);

  Camera camera = scene.cameraOrDefault();
  if (o.width > 0) camera.width = o.width;
  if (o.height > 0) camera.height = o.height;
  PathTracerSettings settings;
  settings.samplesPerPixel = o.spp;
  settings.maxDepth = o.maxDepth;
  settings.seed = o.seed;

  InterruptGuard interruptible;
  Stopwatch renderTime;
  PathTracedImage result = renderPathTraced(scene, camera, settings, console.progress("render"));
  stats.timingsSeconds.render = renderTime.seconds();
  console.finishProgress();
  stats.counts.rays = result.stats.rays;

  if (!o.stats.empty() && o.objectPoints > 0) {
    Stopwatch solveTime;
    PathTracerStats objectStats;
    stats.objects = estimateObjectRadiometry(scene, o.objectPoints, settings, &objectStats,
                                             console.progress("surfaces"));
    console.finishProgress();
    stats.counts.rays += objectStats.rays;
    stats.timingsSeconds.solve = solveTime.seconds();
    stats.absorbedPower = absorbedPower(scene, stats.objects);
  }

  ImageWriteOptions writeOptions;
  writeOptions.exposureEV = o.exposure;
  writeOptions.exrPixelType = o.exrFloat ? ExrPixelType::Float : ExrPixelType::Half;
  writeImage(o.output, result.image, writeOptions);

  const double seconds = total.seconds();
  if (!o.stats.empty()) {
    stats.scene = o.scene;
    stats.method = o.method;
    stats.counts.triangles = scene.triangles.size();
    stats.emittedPower = scene.emittedPower();
    stats.timingsSeconds.total = seconds;
    stats.memoryPeakBytes = peakResidentBytes();
    writeRunStats(o.stats, stats);
  }
  console.info(fmt::format("rendered {} {}x{} at {} spp with {} in {:.2f} s ({:.2f} Mrays/s) -> {}{}",
                           o.scene, camera.width, camera.height, o.spp, o.method, seconds,
                           result.stats.rays / std::max(result.stats.seconds, 1e-9) * 1e-6, o.output,
                           o.stats.empty() ? "" : ", stats -> " + o.stats));
  return 0;
}

}  // namespace

void addRenderCommand(CLI::App& app, Console& console, CommandAction& action) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* sub = app.add_subcommand("render", "Render an image of a scene");
  sub->add_option("scene", o->scene, "Scene file (.json .obj .gltf .glb) or built-in: cornell, "
                                     "cornell-spot, room:N")->required();
  o->outputFlag = sub->add_option("-o,--output", o->output,
                                  "Output image: .png (tone mapped), .exr or .pfm (linear radiance)");
  o->methodFlag = sub->add_option("--method", o->method, "Light transport method")
                      ->check(CLI::IsMember({"pathtrace"}));
  sub->add_option("--width", o->width, "Image width in pixels (default: the scene camera's)")
      ->check(CLI::Range(1, 1 << 15));
  sub->add_option("--height", o->height, "Image height in pixels (default: the scene camera's)")
      ->check(CLI::Range(1, 1 << 15));
  o->sppFlag = sub->add_option("--spp", o->spp, "Path tracer samples per pixel (default 64)")
                   ->check(CLI::Range(1, 1 << 20));
  o->maxDepthFlag = sub->add_option("--max-depth", o->maxDepth, "Path tracer bounce limit")
                        ->check(CLI::Range(1, 100000));
  o->seedFlag = sub->add_option("--seed", o->seed, "Random seed (same seed, same image)");
  sub->add_option("--exposure", o->exposure, "PNG exposure in EV (radiance x 2^EV)");
  sub->add_flag("--exr-float", o->exrFloat, "Write 32-bit float EXR instead of half");
  sub->add_option("--stats", o->stats, "Write the run's numbers to this JSON file");
  sub->add_option("--object-points", o->objectPoints,
                  "Surface points per object for the stats' per-object radiometry (0: skip)")
      ->check(CLI::NonNegativeNumber);
  sub->callback([o, &console, &action] { action = [o, &console] { return runRender(*o, console); }; });
}

}  // namespace rad::cli
