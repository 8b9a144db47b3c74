#pragma once
// One direction of the voxel method: partition the voxels into parallel naive 3D discrete lines
// and let every voxel side gather the radiosity of the voxel before it on its line.
//
// Based on: P. Chatelier and R. Malgouyres, "A low-complexity discrete radiosity method",
// Computers & Graphics 30(1), 2006. For a primitive direction (a, b, c) permuted and signed so that
// a >= b >= c >= 0, voxel (x, y, z) lies on the naive line
//   (floor((a y - b x) / a), floor((a z - c x) / a)) = (y - ceil(b x / a), z - ceil(c x / a)),
// so its line index is a sum of one table lookup per axis. The lines partition space and hold
// one voxel per value of the dominant axis; visiting the cells in a lexicographic order whose
// axes run with the direction's signs meets each line's voxels in order along it, so a table
// holding each line's last voxel pairs every voxel with its predecessor in O(1), no sorting.
//
// What a voxel side sees along its line: the light travelling along the pass direction s reaches
// side e from the first voxel behind it whose surface the backward ray from e's centroid really
// meets. Each line keeps its last few voxels; a voxel is looked through when the ray only grazes
// its surface (it runs in the surface's plane, or the plane is crossed outside that voxel), is
// met by a side facing e (the source) or by a back (blocked). This is the paper's tangent
// correction made exact per side: the voxels of a floor do not hide each other from a wall at a
// grazing angle, and the sides of a thin wall never see through it. Runs of voxels along the
// same planes are kept as one, so long grazing runs cost one slot.

#include "voxel/direction_set.h"
#include "voxel/voxel_grid.h"

#include <glm/vec4.hpp>

#include <span>
#include <vector>

namespace rad {

struct SweepSettings {
  bool tangentCorrection = true;
};

class DiscreteLineSweep {
 public:
  DiscreteLineSweep(const VoxelGrid& grid, const SweepSettings& settings);

  /// Sweeps the direction and its opposite. For each entry e facing back along a pass direction s
  /// (cos = -n_e . s > 0): gathered[e].w += cos * w and gathered[e].rgb += B(source) * cos * w,
  /// w = solidAngle / pi, where the source is the entry of the preceding voxel on e's line that
  /// faces e. `radiosity` is B per entry.
  void sweepPair(const DiscreteDirection& direction, std::span<const Color> radiosity,
                 std::span<glm::vec4> gathered);

  /// The naive line of every cell for a direction (for tests): lines[cell].
  std::vector<uint32_t> lineOfEachCell(const IVec3& step);
  /// Cells in the order a pass along `step` visits them (for tests).
  std::vector<uint32_t> passOrder(const IVec3& step) const;
  size_t lineTableSize() const { return lines_.size(); }

 private:
  static constexpr int kHistory = 5;
  /// The line's last voxels (runs along one plane collapsed), most recent first.
  struct LineState {
    uint32_t stamp = 0;
    uint32_t count = 0;
    int32_t lastDominant = 0;
    uint32_t cells[kHistory] = {};
  };
  enum class Sight { Through, Source, Blocked };
  void prepareLines(const IVec3& step);
  void pass(const IVec3& step, const Vec3& unit, float weight, std::span<const Color> radiosity,
            std::span<glm::vec4> gathered);
  void visitCell(uint32_t cell, uint32_t line, int32_t dominant, const Vec3& unit, float weight,
                 std::span<const Color> radiosity, std::span<glm::vec4> gathered);
  /// How the backward ray from entry e (along -unit) meets cell q; `source` gets the entry of q
  /// it sees when the answer is Source.
  Sight look(uint32_t e, uint32_t q, const Vec3& unit, uint32_t& source) const;
  /// False when a ray from `origin` meeting f's plane at `point` misses f's polygon at a
  /// concave fold with another side of cell q (or has to pass through that side first).
  bool insideFold(uint32_t f, uint32_t q, const Vec3& point, const Vec3& origin) const;
  /// The side of e's own cell that e sees along -unit, if any (faces of an inner edge).
  bool lookWithinCell(uint32_t e, uint32_t cell, const Vec3& unit, uint32_t& source) const;
  /// True when cell p holds the same planes as cell q (a floor, or the two faces of an edge):
  /// consecutive such cells on a line are one run.
  bool continuesPlanes(uint32_t p, uint32_t q) const;
  void remember(LineState& state, uint32_t cell, int32_t dominant) const;

  const VoxelGrid& grid_;
  SweepSettings settings_;
  std::vector<int32_t> lineTable_[3];      ///< per axis: contribution to the flat line index
  std::vector<int32_t> dominantTable_[3];  ///< per axis: contribution to the signed dominant coordinate
  std::vector<LineState> lines_;
  uint32_t stamp_ = 0;
};

}  // namespace rad
