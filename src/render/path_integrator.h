#pragma once
// The estimators of the reference path tracer for one diffuse scene: radiance along a camera
// ray and irradiance at a surface point. Stateless after construction, so one instance serves
// every thread; randomness comes from the caller's Rng.

#include <radiosity/ray_caster.h>
#include <radiosity/scene.h>

#include "core/rng.h"
#include "lighting/direct_lighting.h"

namespace rad {

class PathIntegrator {
 public:
  /// Keeps pointers to `scene` and `caster`, which must outlive it. maxDepth >= 1 counts the
  /// surface vertices at which light is gathered (1: direct light only).
  PathIntegrator(const Scene& scene, const RayCaster& caster, int maxDepth);

  /// Radiance arriving at the ray's origin along -direction (the camera's view of a surface):
  /// its emission plus its reflection of direct and indirect light.
  Color radiance(const Ray& ray, Rng& rng) const;
  /// Irradiance H at point p on a surface with front normal n: the cosine-weighted integral of
  /// incident radiance (direct light by next-event estimation, the rest by one bounce).
  Color irradiance(const Vec3& p, const Vec3& n, Rng& rng) const;
  /// Irradiance at the surface the ray meets, on the side it sees (0 on the back of a one-sided
  /// face, or where it meets nothing): what a false-colour picture shows.
  Color irradianceSeen(const Ray& ray, Rng& rng) const;

 private:
  /// Estimate of the integral of direct incident radiance times cos over the hemisphere of n;
  /// with `misWeighted` the emissive-triangle sample carries its multiple-importance weight
  /// against the cosine bounce, which then adds the emission it hits.
  Color directIntegral(const Vec3& p, const Vec3& n, bool misWeighted, Rng& rng) const;
  /// Radiance along `ray`. bouncePdf < 0: a camera ray, whose first hit adds its full
  /// emission; otherwise the solid-angle density with which a cosine bounce chose the ray.
  Color trace(Ray ray, float bouncePdf, int firstDepth, Rng& rng) const;
  Ray bounce(const Vec3& p, const Vec3& n, float& pdf, Rng& rng) const;

  const Scene* scene_;
  const RayCaster* caster_;
  DirectLighting direct_;
  int maxDepth_;
};

}  // namespace rad
