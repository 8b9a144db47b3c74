#include "scene/polygon.h"

#include <cmath>

namespace rad {

Vec3d newellNormal(std::span<const Vec3> corners) {
  Vec3d n(0.0);
  for (size_t i = 0; i < corners.size(); ++i) {
    const Vec3d a = corners[i];
    const Vec3d b = corners[(i + 1) % corners.size()];
    n += Vec3d((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
  }
  return n;
}

double planeDeviation(std::span<const Vec3> corners) {
  const Vec3d n = newellNormal(corners);
  const double len = glm::length(n);
  if (len == 0.0) return 0.0;
  Vec3d centroid(0.0);
  for (const Vec3& c : corners) centroid += Vec3d(c);
  centroid /= double(corners.size());
  double deviation = 0.0;
  for (const Vec3& c : corners)
    deviation = std::max(deviation, std::abs(glm::dot(Vec3d(c) - centroid, n / len)));
  return deviation;
}

namespace {

// Twice the signed area of the 2D triangle (a, b, c); positive when counter-clockwise.
double orient2d(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

bool insideTriangle(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b,
                    const glm::dvec2& c) {
  return orient2d(a, b, p) >= 0.0 && orient2d(b, c, p) >= 0.0 && orient2d(c, a, p) >= 0.0;
}

}  // namespace

std::vector<UVec3> triangulatePolygon(std::span<const Vec3> corners, const Vec3d& normal) {
  const size_t n = corners.size();
  std::vector<UVec3> triangles;
  if (n < 3) return triangles;
  if (n == 3) return {UVec3(0, 1, 2)};

  // Project onto the plane of the dominant normal axis, keeping the winding counter-clockwise.
  const Vec3d an = glm::abs(normal);
  const int drop = (an.x >= an.y && an.x >= an.z) ? 0 : (an.y >= an.z ? 1 : 2);
  const int u = (drop + 1) % 3, v = (drop + 2) % 3;
  const bool flip = normal[drop] < 0.0;
  std::vector<glm::dvec2> p(n);
  for (size_t i = 0; i < n; ++i) {
    p[i] = glm::dvec2(corners[i][u], corners[i][v]);
    if (flip) p[i].y = -p[i].y;
  }

  std::vector<uint32_t> remaining(n);
  for (size_t i = 0; i < n; ++i) remaining[i] = uint32_t(i);
  size_t guard = 0;
  while (remaining.size() > 3 && guard < n * n) {
    ++guard;
    const size_t m = remaining.size();
    bool clipped = false;
    for (size_t i = 0; i < m && !clipped; ++i) {
      const uint32_t ia = remaining[(i + m - 1) % m], ib = remaining[i],
                     ic = remaining[(i + 1) % m];
      if (orient2d(p[ia], p[ib], p[ic]) <= 0.0) continue;  // reflex or flat corner: not an ear
      bool empty = true;
      for (uint32_t j : remaining) {
        if (j == ia || j == ib || j == ic) continue;
        if (insideTriangle(p[j], p[ia], p[ib], p[ic])) {
          empty = false;
          break;
        }
      }
      if (!empty) continue;
      triangles.emplace_back(ia, ib, ic);
      remaining.erase(remaining.begin() + long(i));
      clipped = true;
    }
    if (!clipped) break;  // self-intersecting or collinear remainder: fan the rest below
  }
  for (size_t i = 1; i + 1 < remaining.size(); ++i)
    triangles.emplace_back(remaining[0], remaining[i], remaining[i + 1]);
  return triangles;
}

}  // namespace rad
