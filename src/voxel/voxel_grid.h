#pragma once
// The surface voxels of a scene, stored for sweeping: cells (occupied voxels) in x-major, then y,
// then z order, grouped into rows (fixed x and y) and slabs (fixed x); each cell holds one entry
// per side of the surfaces crossing it (a thin wall's front and back, a corner's two faces).
// Entries are structure-of-arrays in cell order, so a sweep reads them sequentially.

#include <radiosity/types.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

namespace rad {

using IVec3 = glm::ivec3;

/// A diffuse material as the voxel method sees it: an area-weighted blend of the scene's
/// materials inside one voxel side.
struct VoxelMaterial {
  Color rho{0.0f};
  Color emission{0.0f};  ///< radiance Ke; radiosity E = pi Ke
  bool operator==(const VoxelMaterial&) const = default;
};

/// What a voxel side is made of and whose it is. Sides share a handful of these, so each side
/// keeps an index into them (VoxelGrid::surface: 2 bytes, 4 past 65,536 surfaces).
struct VoxelSurface {
  VoxelMaterial material;
  uint32_t object = 0;    ///< the scene object the side belongs to
  bool backSide = false;  ///< the back of a two-sided face (results per object count fronts)
  /// The scene material whose emission it carries (the one that gave it most where several
  /// did), so that a light group's scale finds it; kNoEmitter where it emits nothing.
  uint32_t emitter = kNoEmitter;
  static constexpr uint32_t kNoEmitter = UINT32_MAX;
  bool operator==(const VoxelSurface&) const = default;
};

/// A unit normal in 16-bit signed fixed point, 6 bytes instead of 12: each component to
/// 1.5e-5, far below the sweep's plane tolerance (a twentieth of a voxel).
struct PackedNormal {
  static constexpr float kScale = 32767.0f;
  std::array<int16_t, 3> v{};
  static PackedNormal pack(const Vec3& n) {
    PackedNormal p;
    for (int k = 0; k < 3; ++k) p.v[size_t(k)] = int16_t(std::lround(n[k] * kScale));
    return p;
  }
  Vec3 unpack() const { return Vec3(float(v[0]), float(v[1]), float(v[2])) * (1.0f / kScale); }
  bool operator==(const PackedNormal&) const = default;
};

/// A side's orientation, 8 bytes that the sweeps read in one aligned load for every side they
/// visit: its unit normal and whether it continues the orientation of the side before it in its
/// cell (the pieces of several objects in one plane, a lamp set in a ceiling, which light sees
/// as one surface).
struct SideOrientation {
  PackedNormal normal;
  bool sharesPrevious = false;
  bool operator==(const SideOrientation&) const = default;
};
static_assert(sizeof(SideOrientation) == 8);

/// Indices that take 2 bytes each while every one is below 65,536 (a scene's distinct surfaces,
/// usually a few dozen) and 4 once one is not: the array widens itself on the first such index.
class NarrowIndices {
 public:
  uint32_t operator[](size_t i) const { return widened_ ? wide_[i] : narrow_[i]; }
  size_t size() const { return widened_ ? wide_.size() : narrow_.size(); }
  void reserve(size_t count) { narrow_.reserve(count); }
  void push_back(uint32_t index);
  size_t memoryBytes() const {
    return narrow_.capacity() * sizeof(uint16_t) + wide_.capacity() * sizeof(uint32_t);
  }
  bool operator==(const NarrowIndices& other) const;

 private:
  std::vector<uint16_t> narrow_;
  std::vector<uint32_t> wide_;
  bool widened_ = false;
};

/// A point of a grid's box in fixed point, 21 bits an axis in one 8-byte word (4 bytes less
/// than three floats): steps of the grid's pointStep, the finest power-of-two fraction of a voxel
/// whose 2^21 steps span the box's widest side (1/8,192 of a voxel up to 256 voxels a side). A
/// point comes back within half a step: below the sweep's edge tolerance (1/1,000 of a voxel)
/// up to 2,048 voxels a side. Floats hold the box's far side to 2^-24 of its size, at most 8
/// times finer, and any point far from the scene's origin coarser.
struct PackedPoint {
  uint64_t bits = 0;
  bool operator==(const PackedPoint&) const = default;
};
/// The point p stands for in a box whose first corner is `origin`, in steps of `step`.
inline Vec3 unpack(PackedPoint p, const Vec3& origin, float step) {
  // Through int32 (the fields fit): a 64-bit unsigned conversion takes several instructions.
  constexpr uint64_t kMask = (uint64_t(1) << 21) - 1;
  const Vec3 steps(float(int32_t(p.bits & kMask)), float(int32_t((p.bits >> 21) & kMask)),
                   float(int32_t(p.bits >> 42)));
  return origin + steps * step;
}

struct VoxelGrid {
  Vec3 origin{0.0f};  ///< corner of voxel (0, 0, 0)
  float voxelSize = 1.0f;
  float pointStep = 1.0f;  ///< a PackedPoint's step (scene units): pointStepFor(dims, voxelSize)
  IVec3 dims{0};           ///< voxels per axis; every coordinate fits in int16

  // Cells, sorted by (x, y, z).
  std::vector<int16_t> cellZ;
  std::vector<uint32_t> cellEntryBegin;  ///< cellCount + 1 offsets into the entries
  // Rows: cells with the same x and y. Slab x holds rows [slabRowBegin[x], slabRowBegin[x+1]).
  std::vector<int16_t> rowY;
  std::vector<uint32_t> rowCellBegin;  ///< rowCount + 1 offsets into the cells
  std::vector<uint32_t> slabRowBegin;  ///< dims.x + 1 offsets into the rows

  // Entries (one per surface side in a cell).
  /// The unit normal, area-weighted mean of the side's triangles, and whether it shares the
  /// orientation of the entry before it.
  std::vector<SideOrientation> orientation;
  /// The area-weighted centroid of the surface inside the voxel (centroidOf).
  std::vector<PackedPoint> centroid;
  /// The surface area the entry stands for, in voxel faces (voxelSize^2), as a half float:
  /// to 2^-12 of its value, 2 bytes (areaOf gives it in scene units^2).
  std::vector<uint16_t> faceArea;
  NarrowIndices surface;  ///< index into surfaces
  std::vector<VoxelSurface> surfaces;

  size_t cellCount() const { return cellZ.size(); }
  size_t entryCount() const { return orientation.size(); }
  size_t rowCount() const { return rowY.size(); }
  /// Integer coordinates of a cell (found from the row structure; O(log rows)).
  IVec3 cellCoordinates(uint32_t cell) const;
  Vec3 unitNormal(size_t entry) const { return orientation[entry].normal.unpack(); }
  Vec3 centroidOf(size_t entry) const { return unpack(centroid[entry]); }
  Vec3 unpack(PackedPoint p) const { return rad::unpack(p, origin, pointStep); }
  /// The nearest point of the box's fixed point to p (inside the box).
  PackedPoint pack(const Vec3d& p) const;
  /// The step of PackedPoints in a box of `dims` voxels: voxelSize / 2^k, the finest whose
  /// 2^21 steps span the widest side.
  static float pointStepFor(const IVec3& dims, float voxelSize);
  /// The surface area the entry stands for (scene units^2).
  float areaOf(size_t entry) const;
  const VoxelMaterial& materialOf(size_t entry) const { return surfaces[surface[entry]].material; }
  uint32_t objectOf(size_t entry) const { return surfaces[surface[entry]].object; }
  Vec3 cellCenter(const IVec3& c) const { return origin + (Vec3(c) + 0.5f) * voxelSize; }
  /// The cell at integer coordinates, or UINT32_MAX when that voxel is empty. O(log) search.
  uint32_t findCell(const IVec3& c) const;
  /// Bytes held by the arrays above.
  size_t memoryBytes() const;
};

}  // namespace rad
