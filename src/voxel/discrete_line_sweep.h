#pragma once
// One direction of the voxel method: partition the voxels into parallel naive 3D discrete lines
// and let every voxel side gather the radiosity of the voxel before it on its line.
//
// Based on: P. Chatelier and R. Malgouyres, "A low-complexity discrete radiosity method",
// Computers & Graphics 30(1), 2006. A voxel's line is a sum of one table lookup per axis
// (line_layout.h); visiting the cells in a lexicographic order whose axes run with the
// direction's signs meets each line's voxels in order along it (pass_order-inl.h), so a record
// holding each line's last voxels pairs every voxel with its predecessor in O(1), no sorting
// (band_scratch.h). What a side sees along its line, and how one traversal along s serves s and
// -s, is the visit's (line_visit-inl.h); the threads share a direction in bands of lines
// (line_bands.h). The pass is compiled for every instruction set Highway targets and runs with
// the widest the processor has (sweep_pass.cpp, its SIMD decoding in sweep_kernels-inl.h); the
// lines and orders tests read are discrete_line_sweep_orders.cpp's.

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "voxel/band_scratch.h"
#include "voxel/direction_set.h"
#include "voxel/line_bands.h"
#include "voxel/line_layout.h"
#include "voxel/side_visibility.h"
#include "voxel/voxel_grid.h"

namespace rad {

struct SweepSettings {
  bool tangentCorrection = true;
};

class DiscreteLineSweep {
 public:
  DiscreteLineSweep(const VoxelGrid& grid, const SweepSettings& settings);
  // One per solve: it holds the line table and each thread's deferred light, too big to copy.
  DiscreteLineSweep(const DiscreteLineSweep&) = delete;
  DiscreteLineSweep& operator=(const DiscreteLineSweep&) = delete;

  /// What the sweeps keep of each side besides the grid's normal and centroid: the radiosity it
  /// sends, in half floats, 6 bytes.
  struct SentLight {
    uint16_t radiosity[3];
  };
  /// What the sweeps read of every side: its normal and centroid (the grid's) and the light it
  /// sends, whose radiosity is the one it sends divided by `scale`, a power of two that keeps
  /// the largest within half floats (halfScaleFor); the sweep multiplies the light it gathers
  /// back by it.
  struct Source {
    const SideOrientation* normals = nullptr;
    std::span<const SentLight> sides;
    float scale = 1.0f;
  };
  /// Packs the radiosity every entry sends, `sends(e)` (finite, >= 0), into `sides`: what the
  /// sweeps read of each side besides the grid's data, prepared once per iteration (B changes
  /// between). Sides of several objects sharing one orientation in a cell (a lamp set in a
  /// ceiling) send light as one surface: their area-weighted mean, whichever of them a line
  /// happens to meet.
  static Source packSides(const VoxelGrid& grid, const std::function<Color(size_t)>& sends,
                          std::span<SentLight> sides);

  /// Sweeps the direction s and its opposite in one traversal along s. For each entry e and each
  /// of d = s, -s with cos = -n_e . d > 0: gathered[e] += B(source) * cos * w, w = solidAngle / pi,
  /// where the source is the side of the voxel before e along d on its line that e's ray meets.
  /// The threads (threadCount()) share the direction: each sweeps bands of its lines, so one
  /// line table and one `gathered` serve them all. A side adds at most one term per pair, from
  /// its own line: the result does not depend on the number of threads, bit for bit.
  void sweepPair(const DiscreteDirection& direction, const Source& source,
                 std::span<Color> gathered, const LineOffset& offset = {});

  /// The threads a sweep uses: the task arena's, or fewer when a global limit (--threads) says so.
  static size_t threadCount();
  /// Sizes each thread's band records for directions of up to `lines` lines (maxLineCount) at
  /// once: records that grow with the directions reallocate, and hold two copies while they do.
  void reserveLines(size_t lines) {
    bandLines_ = std::max(bandLines_, bandLineCapacity(grid_, lines));
  }
  /// The bytes a sweep of `grid` holds for directions of up to `lines` lines (maxLineCount),
  /// known before it is built.
  static size_t workingBytesFor(const VoxelGrid& grid, size_t lines);

  /// The naive line of every cell for a direction (for tests): lines[cell].
  std::vector<uint32_t> lineOfEachCell(const IVec3& step, const LineOffset& offset = {});
  /// Cells in the order a pass along `step` visits them (for tests).
  std::vector<uint32_t> passOrder(const IVec3& step);
  /// The same pass cut into `bands` bands of lines, or more where a band would hold more than
  /// bandLineLimit() lines: the cells each visits, in order.
  std::vector<std::vector<uint32_t>> passOrderInBands(const IVec3& step, size_t bands);
  /// The lines of the direction prepared last: line indices lie in [0, lineCount()).
  size_t lineCount() const { return table_.lineCount(); }
  /// The most lines a band holds: each thread's records, sized for the widest direction yet.
  size_t bandLineLimit() const { return bandLines_; }
  /// Working memory of this sweep: each thread's line records, waiting sides and deferred
  /// light, the cells the bands are balanced on and the folds within cells and with neighbouring
  /// voxels.
  size_t workingBytes() const;

 private:
  /// Numbers the lines of direction `step` (shifted by `offset`) and sizes the bands for them.
  void prepareLines(const IVec3& step, const LineOffset& offset = {});
  /// The cells of one band of the direction prepared last, in pass order (for tests).
  std::vector<uint32_t> cellsInPassOrder(const IVec3& step, const LineBand& band) const;

  const VoxelGrid& grid_;
  SweepSettings settings_;
  /// Read-only and the same for every direction: one for a sweep and all its copies (threads).
  std::shared_ptr<const SideVisibility> visibility_;
  std::vector<uint32_t> occupiedSlabs_;  ///< the x of the slabs that hold cells, ascending
  LineTable table_;                      ///< this direction's
  LineBands bands_;                      ///< this direction's
  size_t bandLines_ = 0;                 ///< the most lines a band holds: its records' size
  tbb::enumerable_thread_specific<sweep::BandScratch> scratch_;
};

}  // namespace rad
