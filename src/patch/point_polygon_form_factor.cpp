// Lambert's contour formula for the point-to-polygon form factor: Cohen and Wallace, "Radiosity
// and Realistic Image Synthesis" (1993), eq. 3.53; as stated and checked in
// shared/reference/VALIDATION.md 1(f), including its pitfalls (atan2 for the edge angles, skip
// zero-length edges, clip to the tangent plane first).
#include "patch/point_polygon_form_factor.h"

#include <cmath>
#include <glm/gtc/constants.hpp>
#include <vector>

namespace rad {

namespace {

// Sutherland-Hodgman against the single plane n . (p - x) >= 0, in coordinates relative to x.
std::vector<Vec3d> clipAbove(const Vec3d& x, const Vec3d& n, std::span<const Vec3d> polygon) {
  std::vector<Vec3d> out;
  out.reserve(polygon.size() + 2);
  for (size_t k = 0; k < polygon.size(); ++k) {
    const Vec3d a = polygon[k] - x, b = polygon[(k + 1) % polygon.size()] - x;
    const double da = glm::dot(n, a), db = glm::dot(n, b);
    if (da >= 0.0) out.push_back(a);
    if ((da >= 0.0) != (db >= 0.0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

}  // namespace

double pointPolygonFormFactor(const Vec3d& x, const Vec3d& n, std::span<const Vec3d> polygon) {
  if (polygon.size() < 3) return 0.0;
  // The polygon's front must face x.
  const Vec3d front = glm::cross(polygon[1] - polygon[0], polygon[2] - polygon[0]);
  if (glm::dot(front, x - polygon[0]) <= 0.0) return 0.0;
  const std::vector<Vec3d> r = clipAbove(x, n, polygon);
  if (r.size() < 3) return 0.0;
  double sum = 0.0;
  for (size_t k = 0; k < r.size(); ++k) {
    const Vec3d& ri = r[k];
    const Vec3d& rj = r[(k + 1) % r.size()];
    const Vec3d c = glm::cross(rj, ri);
    const double len = glm::length(c);
    if (len <= 0.0) continue;
    const double gamma = std::atan2(len, glm::dot(ri, rj));
    sum += gamma * glm::dot(n, c) / len;
  }
  return std::max(0.0, sum / (2.0 * glm::pi<double>()));
}

}  // namespace rad
