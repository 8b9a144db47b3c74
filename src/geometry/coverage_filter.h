#pragma once
// Which rays meet a surface that is not opaque (Material: alpha and transmission). A ray meets a
// point of coverage c with probability c: always or never where c is 0 or 1 (Mask), and for a
// fractional c where a hash of the ray and the triangle falls below c, so that a ray's fate is
// the same on every run, thread and process, while many rays (a hemisphere's, a pixel's) pass in
// the proportion 1 - c. The ray caster asks it from Embree's filter functions, on the triangles
// of materials that are not opaque only.

#include <radiosity/scene.h>

#include <cstdint>
#include <span>

namespace rad {

class CoverageFilter {
 public:
  /// Keeps what the coverage of `triangles` (of `scene`) depends on; no reference to the scene.
  CoverageFilter(const Scene& scene, std::span<const uint32_t> triangles);

  /// True if the ray (origin, direction: its bits, as the caster was given them) meets the
  /// k-th triangle of those given, at barycentrics b.
  bool meets(uint32_t k, Vec2 b, const Vec3& origin, const Vec3& direction) const;

 private:
  /// The triangles alone, each with three vertices of its own, with their materials.
  Scene own_;
};

/// A number in [0, 1) from a ray and a triangle, evenly spread and the same on any machine.
float rayTriangleHash(const Vec3& origin, const Vec3& direction, uint32_t triangle);

}  // namespace rad
