#pragma once
// Objects that move, lit by the static solution (after "real-time radiosity II"'s radiosity
// mapping): a probe at each object's centre (or a grid of probes over a large object, blended by
// inverse squared distance) sees the static scene's light (CubeProbe), and each of its vertices
// takes its irradiance from that view plus the direct light of the point, spot and IES lights by
// shadow rays; hits on the object are shaded by interpolating its vertices' irradiance, smooth
// across its mesh. A ProbeCache keeps the probes of an object that barely moved under unchanged
// lights. What an object reflects goes back to the static scene as six lights (LightType::Object,
// objectLights), one per axis lobe, each leaving from the centroid of the faces that send it:
// lobe k sends P_k max(0, d . e_k) toward d, P_k = sum over the object's triangles facing e_k of
// B A max(0, n . e_k) / pi. The commands solve the static scene again with those lights, its
// point, spot and IES lights' direct light then shadowed by the placed objects; the bounce light
// and the glowing surfaces' light that an object blocks are not taken out of the static solution.

#include <radiosity/placed_objects.h>
#include <radiosity/surface_solution.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "lighting/direct_lighting.h"
#include "probes/cube_probe.h"

namespace rad {

/// What a ProbeCache keeps: by object name and probe, the probes of earlier frames and where
/// they were captured (placed_objects.h).
struct ProbeCache::State {
  struct Probes {
    Vec3 centre{0.0f};
    std::shared_ptr<const CubeProbe> full, bounce;
  };
  std::map<std::string, Probes> probes;
  size_t captures = 0;
};

/// The static solution with the dynamic objects in place, as one SurfaceRadiance over `placed`
/// (Scene::withDynamicObjectsAt): its own triangles shaded by `solution`, the objects' by rho / pi
/// times their vertices' irradiance. Its indirect irradiance (per-pixel pictures add the direct
/// light) is, on an object, its probe's view of what the static surfaces reflect (their emission
/// left out, since the renderer samples the emitters itself). Captures its probes and lights the
/// vertices on construction (in parallel); `staticCaster` is built over the solution's scene,
/// `placedCaster` over `placed` (objects shadow themselves and the scene).
class DynamicObjectLighting : public SurfaceRadiance {
 public:
  DynamicObjectLighting(const Scene& placed, const SurfaceSolution& solution,
                        const RayCaster& staticCaster, const RayCaster& placedCaster,
                        const DynamicObjectSettings& settings = {}, ProbeCache* cache = nullptr);

  Color radiance(const SurfaceHit& hit) const override;
  bool hasIndirectIrradiance() const override { return solution_.hasIndirectIrradiance(); }
  Color indirectIrradiance(const SurfaceHit& hit) const override;
  /// The solution's lights but the objects' own (a shadow ray toward one would stop at its
  /// object); their direct light on the scene is in indirectIrradiance() instead.
  std::span<const Light> directLights() const override { return pointLights_; }
  std::span<const Color> emissionScales() const override { return solution_.emissionScales(); }

  /// Each object's reflected light as six lights (LightType::Object), one per axis lobe, each
  /// from the centroid of the surface facing its way; their group is named after the object.
  /// Shadow rays toward them stop at the object's bounding sphere.
  std::vector<Light> objectLights() const;
  /// Adds the objects to `mesh` (the solution's lit mesh), a group each: their triangles with
  /// the radiance radiance() gives at their corners.
  void appendObjects(LitMesh& mesh) const;
  /// Per object (in order): its name, its area-weighted mean irradiance and its light's lobes.
  std::vector<DynamicObjectSummary> summaries() const;

  /// The irradiance of vertex `v` of `placed` (an object's; 0 for the scene's own), full and
  /// without the lights' and emitters' direct light.
  Color vertexIrradiance(uint32_t v) const { return full_[v]; }
  Color vertexIndirect(uint32_t v) const { return indirect_[v]; }

 private:
  bool isObject(uint32_t triangle) const { return triangle >= placed_.staticTriangles; }
  /// A per-vertex value at a hit on an object's triangle (barycentric interpolation).
  Color atHit(const SurfaceHit& hit, const std::vector<Color>& perVertex) const;

  const Scene& placed_;
  const SurfaceSolution& solution_;
  // Per object of `placed`: the six lobes of its reflected light and where each leaves from.
  struct ObjectLobes {
    bool present = false;
    std::array<Color, 6> lobes{};
    std::array<Vec3, 6> origins{};
  };
  std::vector<ObjectLobes> objectLobes() const;

  std::vector<Vec3> centres_;  ///< per object of `placed` (its own objects' unused)
  std::vector<float> radii_;   ///< per object: its vertices' largest distance from its centre
  std::vector<Light> pointLights_, objectLights_;  ///< the solution's, split by kind
  std::unique_ptr<DirectLighting> fromObjects_;    ///< objectLights_ through the static caster
  std::vector<Color> full_, indirect_;             ///< per vertex of `placed` (objects' only)
};

}  // namespace rad
