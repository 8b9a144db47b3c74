#include "geometry/coverage_filter.h"

#include <bit>

#include "core/rng.h"

namespace rad {

namespace {

uint64_t pair(float a, float b) {
  return uint64_t(std::bit_cast<uint32_t>(a)) | uint64_t(std::bit_cast<uint32_t>(b)) << 32;
}

}  // namespace

float rayTriangleHash(const Vec3& origin, const Vec3& direction, uint32_t triangle) {
  uint64_t h = splitMix64(pair(origin.x, origin.y) + 0x9e3779b97f4a7c15ull);
  h = splitMix64(h ^ pair(origin.z, direction.x));
  h = splitMix64(h ^ pair(direction.y, direction.z));
  h = splitMix64(h ^ triangle);
  return float(h >> 40) * 0x1p-24f;
}

CoverageFilter::CoverageFilter(const Scene& scene, std::span<const uint32_t> triangles) {
  own_.materials = scene.materials;
  const bool mapped = !scene.texcoords.empty(), alpha = !scene.vertexAlpha.empty();
  for (const uint32_t t : triangles) {
    const uint32_t k = uint32_t(own_.triangles.size());
    for (int c = 0; c < 3; ++c) {
      const uint32_t v = scene.triangles[t][c];
      own_.positions.push_back(scene.positions[v]);
      if (mapped) own_.texcoords.push_back(scene.texcoords[v]);
      if (alpha) own_.vertexAlpha.push_back(scene.vertexAlpha[v]);
    }
    own_.triangles.push_back(UVec3(3 * k, 3 * k + 1, 3 * k + 2));
    own_.triangleFace.push_back(k);
    Face face;
    face.material = scene.faceOf(t).material;
    own_.faces.push_back(face);
  }
}

bool CoverageFilter::meets(uint32_t k, Vec2 b, const Vec3& origin, const Vec3& direction) const {
  const float c = own_.coverageAt(k, b);
  if (c >= 1.0f) return true;
  if (c <= 0.0f) return false;
  return rayTriangleHash(origin, direction, k) < c;
}

}  // namespace rad
