#pragma once
// The engine: a scene lit by one method, with the composition every front end needs written
// once. It holds the scene's one ray caster (one BVH, shared by every stage) and the method's
// model, and answers "the solution at time t with these lights": solved or relit with the
// dynamic objects where they are then (their shadows in the lights' direct light, the light they
// reflect as one more bounce), and the objects lit by probes of that solution for pictures,
// exports, the viewer and the stats. `render`, `solve`, `animate` and `serve` all go through it.

#include <radiosity/image.h>
#include <radiosity/placed_objects.h>
#include <radiosity/progress.h>
#include <radiosity/radiosity_method.h>
#include <radiosity/ray_caster.h>
#include <radiosity/relighting.h>
#include <radiosity/scene.h>
#include <radiosity/sensors.h>
#include <radiosity/solver_settings.h>
#include <radiosity/surface_radiance.h>
#include <radiosity/surface_solution.h>

#include <memory>
#include <span>
#include <string>
#include <vector>

namespace rad {

class RadiosityEngine {
 public:
  /// `scene` (which must outlive the engine) lit by the method `settings.method`: builds the
  /// ray caster and, for a method that solves the surfaces, prepares its model. Throws
  /// InputError for an unknown method or bad settings.
  RadiosityEngine(const Scene& scene, MethodSettings settings);
  ~RadiosityEngine();
  RadiosityEngine(const RadiosityEngine&) = delete;
  RadiosityEngine& operator=(const RadiosityEngine&) = delete;

  const Scene& scene() const;
  const RayCaster& caster() const;
  const RadiosityMethod& method() const;
  const MethodSettings& settings() const;
  /// The method's model; throws InputError for a method without a surface solution.
  const MethodModel& model() const;

  /// The solution for `lights` with the dynamic objects placed at `seconds`: a solve, and with
  /// objects a second one with their reflected light as lights and their shadows in the lights'
  /// direct light (the first half of `progress`, then the second). Throws what the method throws.
  std::unique_ptr<SurfaceSolution> solve(std::span<const Light> lights, double seconds,
                                         const ProgressCallback& progress = {}) const;
  /// The solution a solution file keeps, made by this method and settings for the scene's lights.
  std::unique_ptr<SurfaceSolution> load(const std::string& path) const;
  /// A relighting for `lights` (solved, or read from `solutionFile` when it is not empty). Throws
  /// InputError for a method that does not relight, naming those that do.
  std::unique_ptr<Relighting> startRelighting(std::span<const Light> lights,
                                              const std::string& solutionFile,
                                              const RelightSettings& settings,
                                              const ProgressCallback& progress = {}) const;
  /// Brings `relighting` to `lights` with the objects placed at `seconds` (their shadows, and
  /// their reflected light as the relighting's last solution lit them: a frame behind).
  /// `emissionScales` as Relighting::relight.
  const RelightStats& relight(Relighting& relighting, std::span<const Light> lights, double seconds,
                              std::span<const Color> emissionScales = {}) const;

  /// The dynamic objects placed at `seconds`, lit by `solution` (which must outlive the result);
  /// `probes`: those of earlier frames to keep where their objects barely moved (null: none).
  PlacedObjects objectsAt(const SurfaceSolution& solution, double seconds,
                          const DynamicObjectSettings& objects = {},
                          ProbeCache* probes = nullptr) const;
  /// The picture of `solution` through `camera` with the objects placed at `seconds`.
  Image render(const SurfaceSolution& solution, const Camera& camera, double seconds,
               const SurfaceRenderSettings& settings, const DynamicObjectSettings& objects = {},
               ProbeCache* probes = nullptr, const ProgressCallback& progress = {}) const;
  /// The irradiance at each sensor point (sensors.h) of `solution` with the objects placed at
  /// `seconds`: their shadows, and their light as the probes give it.
  std::vector<Color> sensorIrradiance(const SurfaceSolution& solution, double seconds,
                                      std::span<const SensorPoint> points,
                                      const SensorSettings& settings,
                                      const DynamicObjectSettings& objects = {},
                                      const ProgressCallback& progress = {}) const;
  /// The solution's lit mesh with the objects placed at `seconds` (a node each) as binary glTF,
  /// written atomically: SurfaceSolution::exportGlb's file with the objects in it.
  void exportGlb(const SurfaceSolution& solution, double seconds, const std::string& path,
                 float exposureEV = 0.0f) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rad
