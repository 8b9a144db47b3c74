#include "voxel/voxel_irradiance_field.h"

#include <cmath>

namespace rad {

namespace {

// A side faces the point's way within 60 degrees, and its surface passes within 1.5 voxels.
constexpr float kFacingCos = 0.5f;
constexpr float kPlaneDistance = 1.5f;

}  // namespace

bool VoxelIrradianceField::accumulate(const IVec3& c, const Vec3& p, const Vec3& n, float weight,
                                      Color& sum, float& total) const {
  const uint32_t cell = grid_.findCell(c);
  if (cell == UINT32_MAX) return false;
  uint32_t best = UINT32_MAX;
  float bestCos = kFacingCos;
  for (uint32_t e = grid_.cellEntryBegin[cell]; e < grid_.cellEntryBegin[cell + 1]; ++e) {
    const Vec3 normal = grid_.unitNormal(e);
    const float cosine = glm::dot(normal, n);
    const float distance = std::abs(glm::dot(normal, p - grid_.centroidOf(e)));
    if (cosine > bestCos && distance < kPlaneDistance * grid_.voxelSize) bestCos = cosine, best = e;
  }
  if (best == UINT32_MAX) return false;
  sum += weight * irradiance_[best];
  total += weight;
  return true;
}

Color VoxelIrradianceField::at(const Vec3& p, const Vec3& n) const {
  const Vec3 g = (p - grid_.origin) / grid_.voxelSize - 0.5f;
  const IVec3 base = IVec3(glm::floor(g));
  const Vec3 f = g - glm::floor(g);
  Color sum(0.0f);
  float total = 0.0f;
  for (int corner = 0; corner < 8; ++corner) {
    const IVec3 d((corner >> 0) & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    const float w = (d.x ? f.x : 1.0f - f.x) * (d.y ? f.y : 1.0f - f.y) * (d.z ? f.z : 1.0f - f.z);
    accumulate(base + d, p, n, w, sum, total);
  }
  if (total > 1e-4f) return sum / total;
  // Only far corners matched (or none): fall back to the nearest matching sides around.
  const IVec3 home = IVec3(glm::floor((p - grid_.origin) / grid_.voxelSize));
  sum = Color(0.0f);
  total = 0.0f;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const IVec3 c = home + IVec3(dx, dy, dz);
        const Vec3 centre = grid_.cellCenter(c);
        const float d2 = glm::dot(centre - p, centre - p) / (grid_.voxelSize * grid_.voxelSize);
        accumulate(c, p, n, 1.0f / (0.25f + d2), sum, total);
      }
  return total > 0.0f ? sum / total : Color(0.0f);
}

}  // namespace rad
