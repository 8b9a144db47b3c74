// Lambert's contour formula for the point-to-polygon form factor: Cohen and Wallace, "Radiosity and
// Realistic Image Synthesis" (1993), eq. 3.53; as stated and checked in docs/references.md 1(f),
// including its pitfalls (atan2 for the edge angles, skip zero-length edges, clip to the tangent
// plane first).
#include "geometry/point_polygon_form_factor.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>

namespace rad {

namespace {

// Lambert's contour sum over a polygon given vertex by vertex (relative to x), without storing
// it: each edge's angle times the cosine between its plane's normal and n, in the same order as a
// loop over the stored polygon would take them.
class ContourSum {
 public:
  explicit ContourSum(const Vec3d& n) : n_(n) {}

  void add(const Vec3d& r) {
    if (count_++ == 0)
      first_ = r;
    else
      sum_ += edge(previous_, r);
    previous_ = r;
  }

  /// The sum with the closing edge; 0 for fewer than 3 vertices.
  double closed() const { return count_ < 3 ? 0.0 : sum_ + edge(previous_, first_); }

 private:
  double edge(const Vec3d& ri, const Vec3d& rj) const {
    const Vec3d c = glm::cross(rj, ri);
    const double len = glm::length(c);
    if (len <= 0.0) return 0.0;
    const double gamma = std::atan2(len, glm::dot(ri, rj));
    return gamma * glm::dot(n_, c) / len;
  }

  Vec3d n_, first_{0.0}, previous_{0.0};
  double sum_ = 0.0;
  size_t count_ = 0;
};

}  // namespace

double pointPolygonFormFactor(const Vec3d& x, const Vec3d& n, std::span<const Vec3d> polygon) {
  if (polygon.size() < 3) return 0.0;
  // The polygon's front must face x.
  const Vec3d front = glm::cross(polygon[1] - polygon[0], polygon[2] - polygon[0]);
  if (glm::dot(front, x - polygon[0]) <= 0.0) return 0.0;
  // Sutherland-Hodgman against the single plane n . (p - x) >= 0, in coordinates relative to x,
  // each vertex of the clipped polygon going straight into the sum: nothing is allocated.
  ContourSum sum(n);
  for (size_t k = 0; k < polygon.size(); ++k) {
    const Vec3d a = polygon[k] - x, b = polygon[(k + 1) % polygon.size()] - x;
    const double da = glm::dot(n, a), db = glm::dot(n, b);
    if (da >= 0.0) sum.add(a);
    if ((da >= 0.0) != (db >= 0.0)) sum.add(a + (b - a) * (da / (da - db)));
  }
  return std::max(0.0, sum.closed() / (2.0 * glm::pi<double>()));
}

}  // namespace rad
