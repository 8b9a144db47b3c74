#include "picture_options.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <radiosity/error.h>
#include <radiosity/process_memory.h>
#include <radiosity/sensors.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <tuple>

#include "command_support.h"
#include "console.h"
#include "method_options.h"

namespace rad::cli {

namespace {

constexpr long kMaxSide = 1l << 15;  ///< pixels along either side of a picture
// A picture's memory at its peak: its linear radiance (12 bytes), the per-pixel estimates of the
// surface renderer or the path tracer, and the 8-bit copy and encoding of the PNG.
constexpr double kPictureBytesPerPixel = 40.0;

}  // namespace

void PictureOptions::addTo(CLI::App& c) {
  c.add_option("--width", width,
               "Image width in pixels (default: the scene camera's; given alone, the height "
               "keeps the camera's aspect ratio)")
      ->check(CLI::Range(1l, kMaxSide));
  c.add_option("--height", height,
               "Image height in pixels (default: the scene camera's; given alone, the width "
               "keeps the camera's aspect ratio)")
      ->check(CLI::Range(1l, kMaxSide));
  c.add_option("--camera", cameraName,
               "One of the cameras the scene's glTF files carry, by name or index (default: the "
               "scene file's camera, else the first of them)");
  for (auto [flag, value, what] :
       {std::tuple{"--eye", &eye, "Camera position X,Y,Z (overrides the scene's)"},
        std::tuple{"--target", &target, "Point the camera looks at X,Y,Z"},
        std::tuple{"--up", &up, "Camera up direction X,Y,Z"}})
    c.add_option(flag, *value, what)->delimiter(',')->expected(3)->check(finiteNumberIn(-1e9, 1e9));
  c.add_option("--fov", fovDeg, "Vertical field of view in degrees (overrides the camera's)")
      ->check(finiteNumberIn(1e-3, 179.0));
  c.add_option("--exposure", exposure, "PNG exposure in EV (radiance x 2^EV)")
      ->check(finiteNumberIn(-64.0, 64.0));
  c.add_flag("--exr-float", exrFloat, "Write 32-bit float EXR instead of half");
  c.add_option("--direct", direct,
               "patch, voxel: direct light by shadow rays at each pixel (per-pixel, default: "
               "sharp shadows and beam edges) or from the solution (solution)")
      ->check(CLI::IsMember({"per-pixel", "solution"}));
  c.add_option("--emitter-samples", emitterSamples,
               "patch, voxel, per-pixel direct light: area samples of the emitting surfaces per "
               "camera ray (default 8)")
      ->check(CLI::Range(1, 1 << 16));
  c.add_option("--probe-res", probeResolution,
               "patch, voxel: texels a cube face of a dynamic object's probe (default 16)")
      ->check(CLI::Range(1, 1024));
  c.add_option("--probe-spacing", probeSpacing,
               "patch, voxel: a dynamic object larger than this gets a grid of probes at most this "
               "far apart (scene units; default 0: one probe at its centre)")
      ->check(nonNegativeNumber());
  c.add_option("--probe-way", probeWay,
               "patch, voxel: a dynamic object's vertex irradiance from its probe: exact, harmonic "
               "(default) or pattern (the published sampling)")
      ->check(CLI::IsMember({"exact", "harmonic", "pattern"}));
}

namespace {

// The camera --camera names: a name of the files' cameras, else an index into them.
Camera namedCamera(const Scene& scene, const std::string& name) {
  for (const auto& [cameraName, camera] : scene.cameras)
    if (cameraName == name) return camera;
  size_t index = 0;
  const auto [end, ec] = std::from_chars(name.data(), name.data() + name.size(), index);
  if (ec == std::errc() && end == name.data() + name.size() && index < scene.cameras.size())
    return scene.cameras[index].second;
  std::vector<std::string> names;
  for (const auto& [cameraName, camera] : scene.cameras) names.push_back(cameraName);
  throw InputError("--camera " + name,
                   names.empty() ? "the scene's files carry no camera"
                                 : fmt::format("no such camera (the scene's: {}, or an index "
                                               "below {})",
                                               fmt::join(names, ", "), names.size()));
}

}  // namespace

Camera PictureOptions::camera(const Scene& scene) const {
  Camera camera = cameraName.empty() ? scene.cameraOrDefault() : namedCamera(scene, cameraName);
  if (eye.size() == 3) camera.eye = Vec3(eye[0], eye[1], eye[2]);
  if (target.size() == 3) camera.target = Vec3(target[0], target[1], target[2]);
  if (up.size() == 3) camera.up = Vec3(up[0], up[1], up[2]);
  if (fovDeg > 0.0f) camera.fovDeg = fovDeg;
  if (const std::string why = cameraProblem(camera); !why.empty()) {
    const size_t colon = why.find(": ");
    throw InputError("--" + why.substr(0, colon), why.substr(colon + 2));
  }
  camera.up = glm::normalize(camera.up);
  const double aspect = double(camera.width) / double(camera.height);
  if (width > 0) camera.width = width;
  if (height > 0) camera.height = height;
  auto side = [](double pixels) { return int(std::clamp(std::lround(pixels), 1l, kMaxSide)); };
  if (width > 0 && height == 0) camera.height = side(double(width) / aspect);
  if (height > 0 && width == 0) camera.width = side(double(height) * aspect);
  requireMemory(double(camera.width) * double(camera.height) * kPictureBytesPerPixel, "picture",
                fmt::format("{} x {} pixels", camera.width, camera.height),
                "render a smaller picture (--width, --height)");
  return camera;
}

void PictureOptions::addFalseColourTo(CLI::App& c) {
  c.add_option("--false-colour", falseColour,
               "A lighting designer's picture: the irradiance at each pixel in false colour, with "
               "isolines and a legend, in lux (needs the scene's unit) or irradiance (W per square "
               "scene unit)")
      ->check(CLI::IsMember({"lux", "irradiance"}));
  c.add_option("--false-colour-max", falseColourMax,
               "The top of the false colours, in their unit (default: the picture's 98th "
               "percentile, rounded up to a step of the legend)")
      ->check(finiteNumberIn(0.0, 1e30));
}

FalseColourScale PictureOptions::falseColourScale(const Scene& scene) const {
  FalseColourScale scale;
  scale.max = falseColourMax;
  if (direct != "per-pixel")
    throw InputError("--false-colour", "the irradiance at each pixel needs --direct per-pixel");
  if (falseColour == "irradiance") {
    scale.unit = "W/" + scene.unit.symbol() + "^2";
    return scale;
  }
  const std::optional<double> luxPerIrradiance = illuminanceLux(Color(1.0f), scene.unit);
  if (!luxPerIrradiance)
    throw InputError("--false-colour lux",
                     "the scene's length unit is not known (its \"unit\"): lux are per square "
                     "metre; use --false-colour irradiance");
  scale.perIrradiance = *luxPerIrradiance;
  return scale;
}

SurfaceRenderSettings PictureOptions::surfaceSettings(const MethodSettings& run) const {
  SurfaceRenderSettings settings;
  settings.irradiance = run.irradiancePictures;
  settings.samplesPerPixel = run.samplesPerPixel;
  settings.seed = run.seed;
  settings.direct = direct == "solution" ? DirectLightMode::Solution : DirectLightMode::PerPixel;
  settings.emitterSamples = emitterSamples;
  return settings;
}

ImageWriteOptions PictureOptions::writeOptions() const {
  ImageWriteOptions options;
  options.exposureEV = falseColour.empty() ? exposure : 0.0f;  // false colours are the ramp's
  options.exrPixelType = exrFloat ? ExrPixelType::Float : ExrPixelType::Half;
  return options;
}

DynamicObjectSettings PictureOptions::objectSettings() const {
  DynamicObjectSettings objects;
  objects.probeMoveThreshold = probeMoveThreshold;
  objects.probeResolution = probeResolution;
  objects.probeSpacing = probeSpacing;
  objects.way = probeWay == "exact"     ? ProbeIrradiance::Exact
                : probeWay == "pattern" ? ProbeIrradiance::Pattern
                                        : ProbeIrradiance::Harmonic;
  return objects;
}

Image PictureOptions::render(const RadiosityEngine& engine, const SurfaceSolution& solution,
                             const Camera& camera, double seconds, const ProgressCallback& progress,
                             ProbeCache* probes) const {
  return engine.render(solution, camera, seconds, surfaceSettings(engine.settings()),
                       objectSettings(), probes, progress);
}

void PictureOptions::warnOfDynamicObjects(const Scene& scene, const std::string& method,
                                          Console& console) {
  if (scene.dynamicObjects.empty()) return;
  console.warn(fmt::format(
      "{} dynamic object(s) lit by probes of the {} solution, the light they reflect added to it "
      "as one more bounce and their shadows from the lights in it too; the bounce light they "
      "block is not taken out",
      scene.dynamicObjects.size(), method));
}

void PictureOptions::warnIfDirectUnavailable(const SurfaceRadiance& solution,
                                             const std::string& method, Console& console) const {
  if (direct != "per-pixel" || solution.hasIndirectIrradiance()) return;
  console.warn(fmt::format(
      "--direct per-pixel needs the direct light kept apart from the bounces, which this {} "
      "solution does not do: the picture shows the solution's own light",
      method));
}

}  // namespace rad::cli
