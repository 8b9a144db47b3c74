#pragma once
// The options of the commands that make pictures (render, animate): the picture's size, how a
// radiosity solution's direct light is drawn, and how the file is written.

#include <radiosity/false_colour.h>
#include <radiosity/image.h>
#include <radiosity/radiosity_engine.h>
#include <radiosity/scene.h>
#include <radiosity/solver_settings.h>
#include <radiosity/surface_radiance.h>
#include <radiosity/surface_solution.h>

#include <string>
#include <vector>

namespace CLI {
class App;
}  // namespace CLI

namespace rad::cli {

class Console;

struct PictureOptions {
  int width = 0, height = 0;  ///< 0: the scene camera's (a side given alone keeps its aspect)
  float exposure = 0.0f;
  bool exrFloat = false;
  std::string direct = "per-pixel";
  int emitterSamples = SurfaceRenderSettings{}.emitterSamples;
  std::string cameraName;              ///< --camera: one of the files' cameras, by name or index
  std::vector<float> eye, target, up;  ///< --eye, --target, --up: 3 numbers each, or none
  float fovDeg = 0.0f;                 ///< --fov: the vertical field of view; 0: the camera's

  std::string falseColour;      ///< --false-colour: "lux", "irradiance" or "" (radiance)
  double falseColourMax = 0.0;  ///< --false-colour-max: the ramp's top; 0: from the picture

  /// Adds --width, --height, --exposure, --exr-float, --direct, --emitter-samples, --camera,
  /// --eye, --target, --up and --fov.
  void addTo(CLI::App& command);
  /// Adds --false-colour and --false-colour-max (render).
  void addFalseColourTo(CLI::App& command);
  /// The false colours asked for, checked before any work: lux need the scene's unit, and the
  /// irradiance at each pixel per-pixel direct light. Throws InputError naming the option.
  FalseColourScale falseColourScale(const Scene& scene) const;
  /// The scene's camera (or the one --camera names) with what the flags set, at the size asked.
  /// Throws InputError for a camera the scene does not have or a view that is no view.
  Camera camera(const Scene& scene) const;
  /// How a radiosity solution is drawn: camera rays and seed from the run's settings.
  SurfaceRenderSettings surfaceSettings(const MethodSettings& settings) const;
  ImageWriteOptions writeOptions() const;
  /// How dynamic objects are lit: --probe-res, --probe-way, --probe-spacing and
  /// --probe-move-threshold.
  DynamicObjectSettings objectSettings() const;
  /// The picture of `solution` (by `engine`) through `camera`; with the scene's dynamic objects
  /// placed as at `seconds`, each lit by probes of the solution (RadiosityEngine::render).
  /// `probes`: the probes of earlier frames to keep where their objects barely moved (null:
  /// none).
  Image render(const RadiosityEngine& engine, const SurfaceSolution& solution, const Camera& camera,
               double seconds, const ProgressCallback& progress,
               ProbeCache* probes = nullptr) const;
  float probeMoveThreshold = 0.0f;  ///< --probe-move-threshold (animate)
  int probeResolution = 16;         ///< --probe-res: texels a cube face of a dynamic object's probe
  std::string probeWay = "harmonic";  ///< --probe-way: exact, harmonic or pattern
  float probeSpacing = 0.0f;          ///< --probe-spacing: a grid of probes over a large object
  /// Warns, when the scene has dynamic objects, of what their lighting leaves out.
  static void warnOfDynamicObjects(const Scene& scene, const std::string& method, Console& console);
  /// Warns when per-pixel direct light was asked of a solution that cannot give it.
  void warnIfDirectUnavailable(const SurfaceRadiance& solution, const std::string& method,
                               Console& console) const;
};

}  // namespace rad::cli
