#pragma once
// The threads share each direction of the voxel sweep: its line table's rows are cut into bands
// of about equal numbers of cells, and a band's cells are a range of rows in every slab (or, when
// z is dominant, a range of z in every slab, since a line's row then depends on x and z). Bands
// touch disjoint lines and sides, so one accumulator serves all threads, and a side's sum over
// the directions is the same whatever their number. A band's lines are a contiguous range of
// the line numbers, and each thread keeps the records of the band it sweeps only: a band holds
// at most a twenty-fourth of the widest direction's lines and a line per 8 sides (plus a row),
// with one thread as with several, so each thread's records take at most a twenty-fourth of the
// memory a whole table would, and no more than the sides in a mostly empty box, and are reused,
// warm in the cache, from band to band.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "voxel/line_layout.h"
#include "voxel/voxel_grid.h"

namespace rad {

/// The lines one task sweeps: rows [uBegin, uEnd) of the line table, which are the lines
/// [firstLine, firstLine + lineCount). A pass over the cells whose lines lie in a band meets
/// each line's voxels in order, as a pass over all cells does.
struct LineBand {
  int64_t uBegin = 0, uEnd = INT64_MAX;
  uint32_t firstLine = 0, lineCount = 0;
  bool holdsAll(size_t rows) const { return uBegin <= 0 && uEnd >= int64_t(rows); }
};

/// A band holds at most 1 / kBandShareOfLines of a direction's lines (and any one row of it):
/// each thread's records take that much memory. Measured against one table for all lines
/// (room:16, 1-2M voxels): with an eighth, 89-91 B per side instead of 105, the same speed on
/// one thread and on two; the sweeps' instructions on one thread 0.7% fewer (room:4, 30k
/// voxels, R = 8), though a band of a dominant z reads every row of the grid. A sixteenth: 2 B
/// per side less on two threads (2M voxels), 2.3% more instructions, the same speed (runs side
/// by side, 1M voxels: 0.95-1.05). A twenty-fourth since the records grew to 64 bytes: the same
/// memory as 48-byte records at a sixteenth (2M voxels, 2 threads: 63.6 B per voxel against
/// 63.9), 1.0-1.04 times the speed (1M voxels, one thread, runs side by side).
inline constexpr size_t kBandShareOfLines = 24;
/// In a box mostly empty (objects far apart), lines far outnumber sides: there a band holds at
/// most a line per kSidesPerLine sides, so that the records take at most 8 B per side a thread
/// and the sweep's memory grows with the sides, not with the box's cross-section. Two 1 m cubes
/// 100 m apart with a lamp between (400k voxels, R = 8, 2 threads): 245 -> 82.5 B per side,
/// peak 114 -> 47 MB, the sweeps 3.26 -> 2.32 s (the passes skip the empty slabs, which every
/// band walked before). Four cubes at the corners of a 100 m square (200k voxels): 2,254 ->
/// 88.5 B per side, peak 478 -> 31 MB, the sweeps 1.9-2.1 -> 2.2 s (3.3 s before a band skipped
/// the slabs whose rows all lie outside it without a search). In a room a twenty-fourth of the
/// lines is the smaller.
inline constexpr size_t kSidesPerLine = 8;
/// The most lines a band of a direction of `lines` lines holds in `grid`: its records' count.
inline size_t bandLineCapacity(const VoxelGrid& grid, size_t lines) {
  // A row of the table is narrower than the grid's box is wide along all three axes.
  return std::min(lines / kBandShareOfLines, grid.entryCount() / kSidesPerLine) +
         size_t(grid.dims.x + grid.dims.y + grid.dims.z);
}
/// Bands per direction: several per thread, so that a thread that finishes early takes another
/// (the lines' work differs from band to band) and the threads wait little for the last one:
/// 16 a thread. Fewer for a dominant z, whose band reads and cuts every row of the grid (its
/// lines are a range of z, across the rows): 2 a thread.
/// Measured on 2 threads (room:16, 93k voxels, R = 38): with 8 bands a thread for every
/// direction, 97% of the threads' time busy and 10% more time a direction for a dominant z
/// than for x; with 16 and 2, 97% busy and the same time for every axis, 134-137 M visits/s
/// against 121-128.
inline size_t bandCountFor(size_t threads, bool zDominant) {
  return threads > 1 ? (zDominant ? 2 : 16) * threads : 1;
}

/// Cuts a direction's line table into bands, balanced on a sample of the grid's cells.
class LineBands {
  /// The coordinates of every 32nd cell, or of 8,192 cells spread evenly over a larger grid:
  /// what the bands are balanced on (counted for every direction, so no more than that).
  using SampleCell = std::array<int16_t, 3>;
  static constexpr size_t kMaxSamples = 8192;

 public:
  explicit LineBands(const VoxelGrid& grid) : grid_(grid) {}
  /// Cuts `table`'s rows into `count` bands of about equal numbers of cells (counted on a
  /// sample of the cells), and those holding more than `mostLines` lines further.
  void cut(const LineTable& table, size_t count, size_t mostLines);
  const std::vector<LineBand>& bands() const { return bands_; }
  /// Bytes of the sample the bands are balanced on: now, and at most.
  size_t sampleBytes() const { return samples_.capacity() * sizeof(SampleCell); }
  static constexpr size_t kMostSampleBytes = kMaxSamples * sizeof(SampleCell);

 private:
  /// Takes the sample, when first needed: a single thread never reads it.
  void sampleCells();

  const VoxelGrid& grid_;
  std::vector<SampleCell> samples_;
  std::vector<uint32_t> sampledPerRow_;  ///< per line table row, scratch for cut
  std::vector<LineBand> bands_;          ///< the direction's cut last
};

}  // namespace rad
