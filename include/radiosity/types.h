#pragma once
// Basic value types shared by every part of the library: vectors, colours, bounds.

#include <algorithm>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <limits>

namespace rad {

using Vec2 = glm::vec2;
using Vec3 = glm::vec3;
using Vec3d = glm::dvec3;
using UVec3 = glm::uvec3;

/// Linear RGB with Rec. 709 primaries. Used for reflectance (dimensionless), radiance, radiosity
/// and intensity alike; the name of the variable says which quantity it holds.
using Color = glm::vec3;

inline float luminance(const Color& c) {
  return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}
inline float maxComponent(const Color& c) {
  return std::max(c.r, std::max(c.g, c.b));
}
inline float minComponent(const Color& c) {
  return std::min(c.r, std::min(c.g, c.b));
}

/// Axis-aligned bounding box; empty (min > max) until a point is added.
struct Bounds {
  Vec3 min{std::numeric_limits<float>::max()};
  Vec3 max{std::numeric_limits<float>::lowest()};

  void extend(const Vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  bool empty() const { return min.x > max.x; }
  Vec3 extent() const { return empty() ? Vec3(0.0f) : max - min; }
  Vec3 center() const { return 0.5f * (min + max); }
  float diagonal() const { return glm::length(extent()); }
};

}  // namespace rad
