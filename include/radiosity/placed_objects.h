#pragma once
// A scene's dynamic objects placed at one time and lit by a solution of the static scene (after
// "real-time radiosity II"'s radiosity mapping): probes of the static light light their vertices,
// their shadows fall in the lights' direct light, and what they reflect goes back to the scene as
// lights. RadiosityEngine::objectsAt makes one; pictures, exports, the viewer and the stats read
// it.

#include <radiosity/image.h>
#include <radiosity/progress.h>
#include <radiosity/ray_caster.h>
#include <radiosity/scene.h>
#include <radiosity/surface_radiance.h>
#include <radiosity/surface_solution.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace rad {

/// How an object's vertex takes its irradiance from its probe's cube map: every texel (exact),
/// a 9-term spherical-harmonic fit (harmonic) or the published sample pattern (pattern).
enum class ProbeIrradiance { Exact, Harmonic, Pattern };

struct DynamicObjectSettings {
  int probeResolution = 16;  ///< texels a cube face
  ProbeIrradiance way = ProbeIrradiance::Harmonic;
  /// A probe kept from an earlier frame (ProbeCache) is captured again once its object's centre
  /// moved more than this (scene units); 0: whenever it moved at all.
  float probeMoveThreshold = 0.0f;
  /// An object larger than this (scene units) along some axis gets a grid of probes over its
  /// box, at most this far apart, blended at each vertex by inverse squared distance (one
  /// probe's lighting holds only near it); 0: one probe at each object's centre.
  float probeSpacing = 0.0f;
};

/// The probes of earlier frames, by object and probe, so that an object that barely moved under
/// unchanged lights is not captured again. The caller says when the static light changed
/// (invalidate()); it counts the captures.
class ProbeCache {
 public:
  ProbeCache();
  ~ProbeCache();
  /// The static solution's light changed: every probe is captured anew.
  void invalidate();
  size_t captures() const;

  struct State;  ///< the probes kept (src/probes)
  State& state() { return *state_; }

 private:
  std::unique_ptr<State> state_;
};

/// Per dynamic object: its name, its area-weighted mean irradiance and its reflected light's six
/// lobes (W/sr along +x, -x, +y, -y, +z, -z).
struct DynamicObjectSummary {
  std::string name;
  Color meanIrradiance{0.0f};
  std::array<Color, 6> lobes{};
};

class PlacedObjects {
 public:
  ~PlacedObjects();
  PlacedObjects(PlacedObjects&&) noexcept;
  PlacedObjects& operator=(PlacedObjects&&) noexcept;

  /// The scene with its objects in place (the static scene itself when it has none), and the
  /// ray caster over it.
  const Scene& scene() const;
  const RayCaster& caster() const;
  /// The light leaving every surface of scene(): the solution's on the static surfaces, rho / pi
  /// times the probes' irradiance on the objects'.
  const SurfaceRadiance& radiance() const;
  /// Each object's reflected light as six lights (LightType::Object), one per axis lobe.
  std::vector<Light> objectLights() const;
  /// Adds the objects to `mesh` (the solution's lit mesh), a group each.
  void appendObjects(LitMesh& mesh) const;
  std::vector<DynamicObjectSummary> summaries() const;

  struct Impl;
  explicit PlacedObjects(std::unique_ptr<Impl> impl);

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace rad
