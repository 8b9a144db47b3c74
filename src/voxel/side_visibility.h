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

#include <bit>
#include <cmath>
#include <vector>

#include "voxel/voxel_grid.h"

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

  /// How the backward ray from a side (its centroid `point`, which the caller often holds
  /// already, and its `normal`) along -unit meets the sides of `cell`; `source` gets the side it
  /// sees when the answer is Source. A back met where the two sides form a convex edge is passed
  /// (passesConvexEdge).
  Sight look(const Vec3& point, const Vec3& normal, uint32_t cell, const Vec3& unit,
             uint32_t& source) const;
  /// The fold masks of the sides of a cell of several sides: bits 0-14, the sides of the cell
  /// in front of the side's plane (a cell's first 15 sides); bit 15: the side has folds with
  /// sides of neighbouring voxels (neighbourFolds_).
  struct CellFolds {
    const uint16_t* masks;
    uint32_t begin;  ///< the cell's first entry
    uint16_t of(uint32_t f) const { return masks[f - begin]; }
    /// True when side g of the cell stands in front of side f's plane.
    bool inFront(uint32_t f, uint32_t g) const { return (of(f) >> (g - begin)) & 1u; }
    /// False when no other side of the cell stands in front of e: e sees nothing within it.
    bool hasFold(uint32_t e) const { return (of(e) & kSidesInFront) != 0; }
  };
  /// The fold masks of a cell of several sides (found once per visit: several reads).
  CellFolds foldsOf(uint32_t cell) const {
    const uint32_t begin = grid_.cellEntryBegin[cell];
    return {folds_.data() + foldIndex(begin), begin};
  }
  /// The side of e's own cell (whose folds are `folds`) that e sees along -unit, if any (the
  /// faces of an inner edge).
  bool lookWithinCell(uint32_t e, const CellFolds& folds, const Vec3& unit, uint32_t& source) const;
  /// True when cell p holds the same planes as cell q (a floor, or the two faces of an edge):
  /// consecutive such cells on a line are one run.
  bool continuesPlanes(uint32_t p, uint32_t q) const;
  /// Bytes of the fold masks a grid's sides take (foldBytes less the folds with neighbouring
  /// voxels), known before the folds are found.
  static size_t maskBytesFor(const VoxelGrid& grid);
  /// Bytes of the folds within cells and with neighbouring voxels.
  size_t foldBytes() const {
    return folds_.capacity() * sizeof(uint16_t) + severalSided_.capacity() * sizeof(uint64_t) +
           severalBefore_.capacity() * sizeof(uint32_t) +
           neighbourFolds_.capacity() * sizeof(FoldPlane);
  }
  /// Distance under which a point lies in a plane: a grazing line runs inside it.
  float planeTolerance() const { return tolerance_; }
  /// Distance under which a point lies on the edge where two sides meet.
  float edgeTolerance() const { return edge_; }

 private:
  static constexpr uint16_t kSidesInFront = 0x7fff, kNeighbourFolds = 0x8000;
  /// Where the mask of `entry`, a side of a cell of several sides, lies in folds_.
  size_t foldIndex(uint32_t entry) const {
    const uint32_t word = entry / 64, bit = entry % 64;
    const uint64_t below = severalSided_[word] & ((uint64_t(1) << bit) - 1);
    return severalBefore_[word] + size_t(std::popcount(below));
  }
  /// True when the ray from `origin` that met f's plane at `point` (front or back, `met`) met f
  /// itself: its polygon as far as the sides of f's cell and of the cells around bound it.
  /// (Inlined into look: called, it cost 2% more instructions in the sweeps.)
  [[gnu::always_inline]] inline bool meets(uint32_t f, uint32_t cell, const CellFolds& folds,
                                           Sight met, const Vec3& point, const Vec3& origin) const;
  bool insideFold(uint32_t f, const CellFolds& folds, const Vec3& point, const Vec3& origin) const;
  /// False when f meets a side of a neighbouring voxel in a concave fold and the ray from
  /// `origin` to `point` (on f's plane) comes from behind that side or crosses f past it.
  bool insideNeighbourFolds(uint32_t f, const Vec3& point, const Vec3& origin) const;
  void findNeighbourFolds();
  /// False when `point`, on f's plane, lies past a convex edge of f (in front of a side of the
  /// cell that f stands behind and that stands behind f).
  bool insideConvexEdges(uint32_t f, uint32_t cell, const CellFolds& folds,
                         const Vec3& point) const;
  void findFoldsWithinCells();

  /// The plane of a side of a neighbouring voxel that meets `entry` in a concave fold.
  struct FoldPlane {
    uint32_t entry;
    PackedNormal normal;
    float offset;  ///< normal . centroid
  };

  const VoxelGrid& grid_;
  float tolerance_;
  float edge_;  ///< distance under which a point lies on the edge where two sides meet
  /// The fold masks (CellFolds) of the sides of cells of several sides, cell after cell: the
  /// only sides that have folds within their cell or are looked at through them (a single side
  /// is tested inline by the sweep), a few percent of the sides. Computed once: the tests they
  /// save would run for every direction. Until 6 commits after b76a6fa, a mask for every side
  /// (2 bytes a side).
  std::vector<uint16_t> folds_;
  /// A bit per entry, set for the sides of cells of several sides, and the count of set bits
  /// before each 64: where an entry's mask lies in folds_.
  std::vector<uint64_t> severalSided_;
  std::vector<uint32_t> severalBefore_;
  std::vector<FoldPlane> neighbourFolds_;  ///< sorted by entry
};

/// True when a side (`normal`, `centroid`) that met the back of the side at `metCentroid` forms a
/// convex edge with it: each behind the other's plane (the meeting made sure of the one). A
/// curved surface is convex from voxel to voxel: a ray that leaves a column's side near its
/// tangent crosses the plane of the next side of the column from behind, past that side's
/// polygon, in the open. Taken for a back that blocks, 12% of the rays from a ball in a furnace
/// found nothing, and the columns of a generated atrium came out 12% dark.
inline bool passesConvexEdge(const Vec3& normal, const Vec3& centroid, const Vec3& metCentroid,
                             float edge) {
  return glm::dot(normal, metCentroid - centroid) < -edge;
}

/// Normals within about 8 degrees belong to one plane.
inline constexpr float kSamePlaneCos = 0.99f;

}  // namespace rad
