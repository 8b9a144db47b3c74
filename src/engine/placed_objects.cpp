// The dynamic objects placed at one time and lit by a solution (placed_objects.h): the placed
// scene and its ray caster, and DynamicObjectLighting over them; the static scene itself when it
// has no dynamic objects.
#include <radiosity/placed_objects.h>

#include "engine/placed_objects_impl.h"

namespace rad {

PlacedObjects::PlacedObjects(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
PlacedObjects::~PlacedObjects() = default;
PlacedObjects::PlacedObjects(PlacedObjects&&) noexcept = default;
PlacedObjects& PlacedObjects::operator=(PlacedObjects&&) noexcept = default;

const Scene& PlacedObjects::scene() const {
  return impl_->placed ? *impl_->placed : impl_->staticScene;
}

const RayCaster& PlacedObjects::caster() const {
  return impl_->placedCaster ? *impl_->placedCaster : impl_->staticCaster;
}

const SurfaceRadiance& PlacedObjects::radiance() const {
  if (impl_->lighting) return *impl_->lighting;
  return impl_->solution;
}

std::vector<Light> PlacedObjects::objectLights() const {
  return impl_->lighting ? impl_->lighting->objectLights() : std::vector<Light>{};
}

void PlacedObjects::appendObjects(LitMesh& mesh) const {
  if (impl_->lighting) impl_->lighting->appendObjects(mesh);
}

std::vector<DynamicObjectSummary> PlacedObjects::summaries() const {
  return impl_->lighting ? impl_->lighting->summaries() : std::vector<DynamicObjectSummary>{};
}

std::unique_ptr<PlacedObjects::Impl> PlacedObjects::Impl::make(
    const Scene& scene, const RayCaster& caster, const SurfaceSolution& solution, double seconds,
    const DynamicObjectSettings& settings, ProbeCache* probes) {
  auto impl = std::make_unique<Impl>(scene, caster, solution);
  if (scene.dynamicObjects.empty()) return impl;
  impl->placed.emplace(scene.withDynamicObjectsAt(seconds));
  impl->placedCaster = std::make_unique<RayCaster>(*impl->placed);
  impl->lighting = std::make_unique<DynamicObjectLighting>(*impl->placed, solution, caster,
                                                           *impl->placedCaster, settings, probes);
  return impl;
}

}  // namespace rad
