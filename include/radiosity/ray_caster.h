#pragma once
// Ray queries against a Scene's triangles: closest hit and occlusion, single or batched.
// The only place that knows about Embree (ray_caster.cpp); everything else sees these types.

#include <radiosity/scene.h>
#include <radiosity/types.h>

#include <cstdint>
#include <limits>
#include <memory>
#include <span>

namespace rad {

inline constexpr uint32_t kNoHit = ~0u;

/// A ray; hits count only for tNear <= t <= tFar, with t measured in units of |direction|.
struct Ray {
  Vec3 origin{0.0f};
  Vec3 direction{0.0f, 0.0f, 1.0f};
  float tNear = 0.0f;
  float tFar = std::numeric_limits<float>::infinity();
};

struct Hit {
  uint32_t triangle = kNoHit;                               ///< index into Scene::triangles
  float distance = std::numeric_limits<float>::infinity();  ///< ray parameter t of the hit
  /// (u, v): the hit point is (1-u-v) * p0 + u * p1 + v * p2 of the triangle's corners.
  Vec2 barycentric{0.0f};
  Vec3 geometricNormal{0.0f};  ///< unit normal of the triangle's front (CCW) side
  bool frontFace = false;      ///< the ray arrived on the front side

  bool valid() const { return triangle != kNoHit; }
};

/// Built once from a scene (the scene's geometry must not change afterwards; the RayCaster
/// keeps no reference to it). Every surface blocks rays from both sides, where it is not opaque
/// with the probability its coverage gives (Scene::coverageAt; a ray passing where a hash of it
/// and the triangle says, the same on every run: geometry/coverage_filter.h). All queries are
/// safe from many threads at once. Throws std::runtime_error if Embree fails.
class RayCaster {
 public:
  explicit RayCaster(const Scene& scene);
  ~RayCaster();
  RayCaster(RayCaster&&) noexcept;
  RayCaster& operator=(RayCaster&&) noexcept;
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  /// The closest hit along the ray, or an invalid Hit.
  Hit intersect(const Ray& ray) const;
  /// True if any surface lies on the ray within [tNear, tFar].
  bool occluded(const Ray& ray) const;
  /// Batched forms: hits[i] / occluded[i] (0 or 1) for rays[i]; the spans must be equally long.
  void intersect(std::span<const Ray> rays, std::span<Hit> hits) const;
  void occluded(std::span<const Ray> rays, std::span<uint8_t> occluded) const;

  /// Rays traced so far by this caster (closest-hit and occlusion, from every thread). Exact
  /// only while no query is in flight.
  uint64_t raysCast() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rad
