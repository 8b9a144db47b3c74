#pragma once
// What a PlacedObjects holds (placed_objects.h); the engine makes them.

#include <radiosity/placed_objects.h>

#include <memory>
#include <optional>

#include "probes/dynamic_objects.h"

namespace rad {

struct PlacedObjects::Impl {
  Impl(const Scene& scene, const RayCaster& caster, const SurfaceSolution& lit)
      : staticScene(scene), staticCaster(caster), solution(lit) {}
  /// The objects of `scene` placed at `seconds`, lit by `solution`; nothing placed when the
  /// scene has no dynamic objects.
  static std::unique_ptr<Impl> make(const Scene& scene, const RayCaster& caster,
                                    const SurfaceSolution& solution, double seconds,
                                    const DynamicObjectSettings& settings, ProbeCache* probes);

  const Scene& staticScene;
  const RayCaster& staticCaster;
  const SurfaceSolution& solution;
  std::optional<Scene> placed;  ///< with objects only; the lighting keeps a reference to it
  std::unique_ptr<RayCaster> placedCaster;
  std::unique_ptr<DynamicObjectLighting> lighting;
};

}  // namespace rad
