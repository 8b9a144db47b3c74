#pragma once
// What a voxel side sees of another voxel along a discrete line: the geometric tests behind the
// voxel sweep's visibility, for cells that hold several sides (edges, corners, thin walls).
//
// The voxels know planes (a side's normal and centroid), not polygons. The backward ray from a
// side's centroid meets the plane of side f at t = height / approach when the signs agree; a
// ray in the plane or leaving it grazes f and passes. The nearest plane met decides: its front
// is the source of light, its back blocks. Where two sides of a cell form a concave fold (each
// in front of the other, like a room's inner edge), each side's polygon ends at the other's
// plane, which keeps light from turning around the outside of a convex edge; a fold with a side
// of a neighbouring voxel bounds a side's front the same way. Where they meet at a convex edge
// (each behind the other, a box's faces), a back met past the edge is the open: passed.

#include "voxel/voxel_grid.h"

#include <cmath>
#include <vector>

namespace rad {

enum class Sight { Through, Source, Blocked };

/// What the backward ray from a point meets at a side's plane, given the point's height above the
/// plane and the dot of the plane's normal with the direction the light travels: grazing (within
/// `tolerance`) or on a ray that never crosses the plane it passes; otherwise it meets the front
/// (the source) or the back (blocked).
inline Sight planeSight(float height, float approach, float tolerance) {
  if (std::abs(height) <= tolerance || height * approach <= 0.0f) return Sight::Through;
  return height > 0.0f ? Sight::Source : Sight::Blocked;
}

class SideVisibility {
 public:
  explicit SideVisibility(const VoxelGrid& grid);

  /// How the backward ray from a point (along -unit) meets the sides of `cell`; `source` gets
  /// the side it sees when the answer is Source. The point is a side's centroid, which the
  /// caller often holds already (the side was visited long ago).
  Sight look(const Vec3& point, uint32_t cell, const Vec3& unit, uint32_t& source) const;
  /// The side of e's own cell that e sees along -unit, if any (the faces of an inner edge).
  bool lookWithinCell(uint32_t e, uint32_t cell, const Vec3& unit, uint32_t& source) const;
  /// False when no other side of e's cell stands in front of e: e sees nothing within its cell.
  bool hasFold(uint32_t e) const { return (frontOf_[e] & kSidesInFront) != 0; }
  /// True when cell p holds the same planes as cell q (a floor, or the two faces of an edge):
  /// consecutive such cells on a line are one run.
  bool continuesPlanes(uint32_t p, uint32_t q) const;
  /// Bytes of the folds with neighbouring voxels (the masks, 2 bytes a side, are not counted).
  size_t neighbourFoldBytes() const { return neighbourFolds_.capacity() * sizeof(FoldPlane); }
  /// Distance under which a point lies in a plane: a grazing line runs inside it.
  float planeTolerance() const { return tolerance_; }

 private:
  /// True when the ray from `origin` that met f's plane at `point` (front or back, `met`) met f
  /// itself: its polygon as far as the sides of f's cell and of the cells around bound it.
  /// (Inlined into look: called, it cost 2% more instructions in the sweeps.)
  [[gnu::always_inline]] inline bool meets(uint32_t f, uint32_t cell, Sight met,
                                           const Vec3& point, const Vec3& origin) const;
  bool insideFold(uint32_t f, uint32_t cell, const Vec3& point, const Vec3& origin) const;
  /// False when f meets a side of a neighbouring voxel in a concave fold and the ray from
  /// `origin` to `point` (on f's plane) comes from behind that side or crosses f past it.
  bool insideNeighbourFolds(uint32_t f, const Vec3& point, const Vec3& origin) const;
  void findNeighbourFolds();
  /// False when `point`, on f's plane, lies past a convex edge of f (in front of a side of the
  /// cell that f stands behind and that stands behind f).
  bool insideConvexEdges(uint32_t f, uint32_t cell, const Vec3& point) const;
  /// True when side g of f's cell (whose first side is `cellBegin`) stands in front of f's plane.
  bool inFront(uint32_t f, uint32_t g, uint32_t cellBegin) const {
    return (frontOf_[f] >> (g - cellBegin)) & 1u;
  }

  /// frontOf_ bits 0-14: the sides of the cell in front of the entry's plane (a cell's first 15
  /// sides); bit 15: the entry has folds with sides of neighbouring voxels (neighbourFolds_).
  static constexpr uint16_t kSidesInFront = 0x7fff, kNeighbourFolds = 0x8000;
  /// The plane of a side of a neighbouring voxel that meets `entry` in a concave fold.
  struct FoldPlane {
    uint32_t entry;
    PackedNormal normal;
    float offset;  ///< normal . centroid
  };

  const VoxelGrid& grid_;
  float tolerance_;
  float edge_;  ///< distance under which a point lies on the edge where two sides meet
  /// Per entry: bit j set when the cell's j-th side stands in front of the entry's plane (the
  /// two form a concave fold). Computed once: the tests it saves would run for every direction.
  std::vector<uint16_t> frontOf_;
  std::vector<FoldPlane> neighbourFolds_;  ///< sorted by entry
};

/// Normals within about 8 degrees belong to one plane.
inline constexpr float kSamePlaneCos = 0.99f;

}  // namespace rad
