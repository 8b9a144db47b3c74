#pragma once
// The naive 3D discrete lines of one direction, numbered so that a voxel's line is a sum of one
// table lookup per axis.
//
// Based on: P. Chatelier and R. Malgouyres, "A low-complexity discrete radiosity method",
// Computers & Graphics 30(1), 2006. For a primitive direction (a, b, c) permuted and signed so that
// a >= b >= c >= 0, voxel (x, y, z) lies on the naive line
//   (floor((a y - b x) / a), floor((a z - c x) / a)) = (y - ceil(b x / a), z - ceil(c x / a)),
// so its line index is a sum of one table lookup per axis. The lines partition space and hold
// one voxel per value of the dominant axis.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "voxel/voxel_grid.h"

namespace rad {

/// Shifts a direction's lines: voxel (x, y, z) of the naive line (floor((a y - b x + u) / a),
/// floor((a z - c x + v) / a)), 0 <= u, v < a. Still naive lines that partition space; a new
/// shift each iteration keeps the lines' pattern from repeating (aliasing) between bounces.
struct LineOffset {
  int64_t u = 0, v = 0;
};

/// A direction's lines as coordinates (U, V) >= 0, U = u[0][t0] + u[1][t1] (+ u[2][t2] = 0)
/// and likewise V, with t_k the cell's coordinate along axes[k] (axes[0] the dominant one,
/// axes[2] the innermost other axis a pass walks): the naive line
/// (floor((a y - b x + u) / a), floor((a z - c x + v) / a)) shifted to start at 0. The lines
/// of row U lie in [vLow[U], vHigh[U]]: the grid's box seen along the direction, a hexagon
/// rather than its bounding parallelogram (a quarter fewer lines for a diagonal).
struct LineLayout {
  std::array<int, 3> axes;
  std::array<std::vector<int64_t>, 3> u, v;
  std::vector<int64_t> vLow, vHigh;
  /// Lays out the lines of direction `step`, shifted by `offset`, in a box of `dims` voxels.
  void layOut(const IVec3& dims, const IVec3& step, const LineOffset& offset);
};

/// The line of every voxel along a direction: line = rowStart[U] + V, where (U, V) =
/// uv[0][x] + uv[1][y] + uv[2][z], U << 32 | V (the sum never carries). Row U of the table
/// holds only the V that the grid's box reaches (LineLayout's hexagon), so lines are numbered
/// densely in [0, lineCount()).
struct LineTable {
  std::vector<uint64_t> uv[3];       ///< per axis: its contribution to the line's (U, V)
  std::vector<int32_t> dominant[3];  ///< per axis: its contribution to the signed dominant one
  std::vector<int32_t> rowStart;     ///< per U: the index of line (U, 0)
  LineLayout layout;

  /// Numbers the lines of direction `step` shifted by `offset` in `grid`'s box; throws
  /// InputError where they are more than 32-bit indices number (checkLineCount).
  void prepare(const VoxelGrid& grid, const IVec3& step, const LineOffset& offset);
  size_t lineCount() const { return lineCount_; }
  size_t rowCount() const { return rowStart.size(); }
  /// The index of row U's first line (U = rowCount(): the line count).
  uint32_t rowFirstLine(size_t row) const {
    return row < rowStart.size() ? uint32_t(rowStart[row] + layout.vLow[row])
                                 : uint32_t(lineCount_);
  }
  bool zDominant() const { return layout.axes[0] == 2; }
  /// Row U of the voxel at (x, y, z).
  size_t rowOf(size_t x, size_t y, size_t z) const {
    return size_t((uv[0][x] + uv[1][y] + uv[2][z]) >> 32);
  }

 private:
  size_t lineCount_ = 0;
};

/// An upper bound of a direction's line count over the directions `steps` and any LineOffset,
/// known before any is prepared (what the sweep's records are sized for).
size_t maxLineCount(const VoxelGrid& grid, std::span<const IVec3> steps);
/// Throws InputError when a direction of `lines` lines is more than the sweep can number
/// (line indices are 32-bit): a grid whose box is very large in voxels, however few it holds.
void checkLineCount(const VoxelGrid& grid, size_t lines);

}  // namespace rad
