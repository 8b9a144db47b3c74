#pragma once
// The seam every light-transport method stands behind. A method is found by name in one registry
// (radiosityMethod("patch")); the commands, the viewer's server and the settings table ask it
// what it can do (MethodCapabilities) instead of knowing which one it is. A method that solves
// the surfaces prepares a model once per geometry (MethodModel) and solves it per light state
// into a SurfaceSolution; one that makes pictures by itself (the path tracer) renders the scene
// as it is. Adding a method is a folder that implements this interface and one registration.

#include <radiosity/image.h>
#include <radiosity/object_radiometry.h>
#include <radiosity/progress.h>
#include <radiosity/ray_caster.h>
#include <radiosity/relighting.h>
#include <radiosity/scene.h>
#include <radiosity/sensors.h>
#include <radiosity/solver_settings.h>
#include <radiosity/surface_solution.h>

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rad {

/// The half of a surface method done once per geometry (a mesh, a voxel grid, form factors).
class MethodModel {
 public:
  virtual ~MethodModel() = default;
  /// What a progress bar of solve() says it is doing, and what ends it.
  virtual std::string solveLabel() const = 0;
  /// The solution with `lights` in place of the scene's own, their direct light shadowed by
  /// `shadowCaster` when given (the scene with its dynamic objects placed), which must outlive
  /// the call. Throws rad::Cancelled if `progress` returns false.
  virtual std::unique_ptr<SurfaceSolution> solve(std::span<const Light> lights,
                                                 const RayCaster* shadowCaster,
                                                 const ProgressCallback& progress) const = 0;
  /// saveSolution: the solution a solution file keeps, made by this model for `lights`. Throws
  /// InputError naming the file for one that does not fit; without the capability, always.
  virtual std::unique_ptr<SurfaceSolution> load(const std::string& path,
                                                std::span<const Light> lights) const;
  /// relight: a solution kept up to date as the lights change, solved for `lights` (or read from
  /// `solutionFile` when it is not empty). Throws InputError without the capability.
  virtual std::unique_ptr<Relighting> startRelighting(std::span<const Light> lights,
                                                      const std::string& solutionFile,
                                                      const RelightSettings& settings,
                                                      const ProgressCallback& progress) const;
};

/// A picture a method made by itself, and what it cost.
struct RenderedPicture {
  Image image;  ///< linear radiance
  uint64_t rays = 0;
  std::vector<std::string> warnings;
  std::string resumed;  ///< what a checkpoint brought, said to the user; empty: nothing
};

/// Per-object means a picture method estimated, and the rays they took.
struct EstimatedObjects {
  std::vector<ObjectRadiometry> objects;
  uint64_t rays = 0;
};

/// Irradiance at sensor points a picture method estimated, and the rays it took.
struct EstimatedSensors {
  std::vector<Color> irradiance;  ///< W per square scene unit, a point each
  uint64_t rays = 0;
};

class RadiosityMethod {
 public:
  virtual ~RadiosityMethod() = default;
  /// The name --method and the scene's "solver" key take, and files record.
  virtual std::string name() const = 0;
  /// The heading of its settings in --help, e.g. "Patch method".
  virtual std::string settingsGroup() const = 0;
  virtual MethodCapabilities capabilities() const = 0;
  /// Its own settings: each a flag, a scene "solver" key and a stats entry, stored in its own
  /// section of MethodSettings. The general ones (solver_settings.h) are not among them.
  virtual std::vector<SettingDeclaration> settingDeclarations() const = 0;
  /// Camera rays a pixel when a run does not say (spp).
  virtual int defaultSamplesPerPixel() const { return 16; }

  /// surfaceSolution: meshes (or voxelizes) `scene` under `settings`; scene and caster must
  /// outlive the model and its solutions. Throws InputError for bad settings.
  virtual std::unique_ptr<MethodModel> prepare(const Scene& scene, const RayCaster& caster,
                                               const MethodSettings& settings) const;
  /// Without surfaceSolution: the picture of `scene` as it is (its objects placed, its emitters
  /// scaled) through `camera`.
  virtual RenderedPicture renderPicture(const Scene& scene, const RayCaster& caster,
                                        const Camera& camera, const MethodSettings& settings,
                                        const ProgressCallback& progress) const;
  /// Without surfaceSolution: each object's means at `pointsPerObject` points.
  virtual EstimatedObjects estimateObjects(const Scene& scene, const RayCaster& caster,
                                           int pointsPerObject, const MethodSettings& settings,
                                           const ProgressCallback& progress) const;
  /// Without surfaceSolution: the irradiance at each sensor point (a surface solution's is the
  /// engine's, RadiosityEngine::sensorIrradiance).
  virtual EstimatedSensors estimateSensors(const Scene& scene, const RayCaster& caster,
                                           std::span<const SensorPoint> points,
                                           const SensorSettings& sensors,
                                           const MethodSettings& settings,
                                           const ProgressCallback& progress) const;
};

/// Every registered method, built-in ones first ("pathtrace", "patch", "voxel").
std::vector<const RadiosityMethod*> radiosityMethods();
/// The method of that name. Throws InputError naming the methods there are.
const RadiosityMethod& radiosityMethod(std::string_view name);
/// The method of that name, or nullptr.
const RadiosityMethod* findRadiosityMethod(std::string_view name);
/// Adds a method (before any run reads the settings table: the table grows by its settings).
/// Throws std::invalid_argument for a name that is taken.
void registerRadiosityMethod(std::unique_ptr<RadiosityMethod> method);
/// The names of the methods that have a capability, e.g.
/// methodsWith(&MethodCapabilities::relight): for the message that refuses the others.
std::vector<std::string> methodsWith(bool MethodCapabilities::*capability);

}  // namespace rad
