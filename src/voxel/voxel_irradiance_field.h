#pragma once
// Smooth irradiance from the voxel solution at any surface point: trilinear weights over the
// eight voxel centres around the point, each voxel contributing its side that faces the point's
// way and lies in the point's surface, renormalized over the voxels that have such a side.

#include <span>

#include "voxel/voxel_grid.h"

namespace rad {

class VoxelIrradianceField {
 public:
  /// Keeps references: `grid` and `irradiance` (H per entry) must outlive the field.
  VoxelIrradianceField(const VoxelGrid& grid, std::span<const Color> irradiance)
      : grid_(grid), irradiance_(irradiance) {}

  /// Irradiance at point p of a surface with unit normal n; black where no voxel side nearby
  /// faces that way.
  Color at(const Vec3& p, const Vec3& n) const;

 private:
  /// Adds the matching side of the cell at c, weighted: returns false if it has none.
  bool accumulate(const IVec3& c, const Vec3& p, const Vec3& n, float weight, Color& sum,
                  float& total) const;

  const VoxelGrid& grid_;
  std::span<const Color> irradiance_;
};

}  // namespace rad
