// The engine (radiosity_engine.h): one ray caster and one model for a scene, and the dynamic
// objects' part in every solve, relight, picture and export, written here once.
#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/gltf_export.h>
#include <radiosity/radiosity_engine.h>

#include "engine/placed_objects_impl.h"

namespace rad {

struct RadiosityEngine::Impl {
  Impl(const Scene& s, MethodSettings m)
      : scene(s), settings(std::move(m)), method(radiosityMethod(settings.method)), caster(s) {
    if (method.capabilities().surfaceSolution) model = method.prepare(scene, caster, settings);
  }
  const Scene& scene;
  MethodSettings settings;
  const RadiosityMethod& method;
  RayCaster caster;  ///< the run's one BVH
  std::unique_ptr<MethodModel> model;
};

RadiosityEngine::RadiosityEngine(const Scene& scene, MethodSettings settings)
    : impl_(std::make_unique<Impl>(scene, std::move(settings))) {}
RadiosityEngine::~RadiosityEngine() = default;

const Scene& RadiosityEngine::scene() const {
  return impl_->scene;
}
const RayCaster& RadiosityEngine::caster() const {
  return impl_->caster;
}
const RadiosityMethod& RadiosityEngine::method() const {
  return impl_->method;
}
const MethodSettings& RadiosityEngine::settings() const {
  return impl_->settings;
}

const MethodModel& RadiosityEngine::model() const {
  if (!impl_->model)
    throw InputError(
        "--method " + impl_->method.name(),
        fmt::format("renders pictures only; the methods that solve the surfaces: {}",
                    fmt::join(methodsWith(&MethodCapabilities::surfaceSolution), ", ")));
  return *impl_->model;
}

std::unique_ptr<SurfaceSolution> RadiosityEngine::solve(std::span<const Light> lights,
                                                        double seconds,
                                                        const ProgressCallback& progress) const {
  const Scene& scene = impl_->scene;
  const bool objects = !scene.dynamicObjects.empty();
  std::unique_ptr<SurfaceSolution> solution =
      model().solve(lights, nullptr, objects ? progressPart(progress, 0, 2) : progress);
  if (!objects) return solution;
  // Once more with the objects in place: their reflected light as lights, and their shadows in
  // the lights' direct light.
  const PlacedObjects placed = objectsAt(*solution, seconds);
  std::vector<Light> withObjects(lights.begin(), lights.end());
  for (const Light& l : placed.objectLights()) withObjects.push_back(l);
  return model().solve(withObjects, &placed.caster(), progressPart(progress, 1, 2));
}

std::unique_ptr<SurfaceSolution> RadiosityEngine::load(const std::string& path) const {
  return model().load(path, impl_->scene.lights);
}

std::unique_ptr<Relighting> RadiosityEngine::startRelighting(
    std::span<const Light> lights, const std::string& solutionFile, const RelightSettings& settings,
    const ProgressCallback& progress) const {
  return model().startRelighting(lights, solutionFile, settings, progress);
}

const RelightStats& RadiosityEngine::relight(Relighting& relighting, std::span<const Light> lights,
                                             double seconds,
                                             std::span<const Color> emissionScales) const {
  if (impl_->scene.dynamicObjects.empty()) return relighting.relight(lights, emissionScales);
  // The objects in place: their shadows, and their reflected light as the last solution lit
  // them (a frame behind).
  const PlacedObjects placed = objectsAt(relighting.solution(), seconds);
  std::vector<Light> withObjects(lights.begin(), lights.end());
  for (const Light& l : placed.objectLights()) withObjects.push_back(l);
  return relighting.relight(withObjects, emissionScales, &placed.caster());
}

PlacedObjects RadiosityEngine::objectsAt(const SurfaceSolution& solution, double seconds,
                                         const DynamicObjectSettings& objects,
                                         ProbeCache* probes) const {
  return PlacedObjects(
      PlacedObjects::Impl::make(impl_->scene, impl_->caster, solution, seconds, objects, probes));
}

Image RadiosityEngine::render(const SurfaceSolution& solution, const Camera& camera, double seconds,
                              const SurfaceRenderSettings& settings,
                              const DynamicObjectSettings& objects, ProbeCache* probes,
                              const ProgressCallback& progress) const {
  const PlacedObjects placed = objectsAt(solution, seconds, objects, probes);
  return renderSurfaceRadiance(placed.scene(), placed.caster(), camera, placed.radiance(), settings,
                               progress);
}

std::vector<Color> RadiosityEngine::sensorIrradiance(const SurfaceSolution& solution,
                                                     double seconds,
                                                     std::span<const SensorPoint> points,
                                                     const SensorSettings& settings,
                                                     const DynamicObjectSettings& objects,
                                                     const ProgressCallback& progress) const {
  const PlacedObjects placed = objectsAt(solution, seconds, objects);
  return rad::sensorIrradiance(placed.scene(), placed.caster(), placed.radiance(), points, settings,
                               progress);
}

void RadiosityEngine::exportGlb(const SurfaceSolution& solution, double seconds,
                                const std::string& path, float exposureEV) const {
  if (impl_->scene.dynamicObjects.empty()) return solution.exportGlb(path, exposureEV);
  LitMesh mesh = solution.litMesh();
  objectsAt(solution, seconds).appendObjects(mesh);
  writeLitMeshGlb(path, mesh, exposureEV);
}

}  // namespace rad
