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
// What a voxel side sees along its line: the light travelling along s reaches side e from the
// first voxel behind it whose surface the backward ray from e's centroid really meets
// (side_visibility.h). One traversal along s serves s and -s: a side facing back looks at the
// voxels behind it at once; a side facing ahead waits on its line's record until the next voxel
// arrives, and its light is added later in batches (it was visited long ago). Each line keeps its
// last voxel (plane, radiosity, centroid) inline and the two before it by reference, so that the
// common case touches one line record and nothing else. A voxel is looked through when the ray
// only grazes its surface: this is the paper's tangent correction made exact per side; the
// voxels of a floor do not hide each other from a wall at a grazing angle, and the sides of a
// thin wall never see through it. Runs of voxels along the same planes are kept as one, so long
// grazing runs cost one slot.
//
// The threads share each direction: the line table's rows are cut into bands of about equal
// numbers of cells, and a band's cells are a range of rows in every slab (or, when z is
// dominant, a range of z in every slab, since a line's row then depends on x and z).
// Bands touch disjoint lines and sides, so one accumulator serves all threads, and a side's sum
// over the directions is the same whatever their number. A band's lines are a contiguous range
// of the line numbers, and each thread keeps the records of the band it sweeps only: a band holds
// at most a twenty-fourth of the widest direction's lines and a line per 8 sides (plus a row),
// with one thread as with several, so each thread's records take at most a twenty-fourth of the
// memory a whole table would, and no more than the sides in a mostly empty box, and are reused,
// warm in the cache, from band to band.

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "voxel/direction_set.h"
#include "voxel/side_visibility.h"
#include "voxel/voxel_grid.h"

namespace rad {

struct SweepSettings {
  bool tangentCorrection = true;
};

/// Shifts a direction's lines: voxel (x, y, z) of the naive line (floor((a y - b x + u) / a),
/// floor((a z - c x + v) / a)), 0 <= u, v < a. Still naive lines that partition space; a new
/// shift each iteration keeps the lines' pattern from repeating (aliasing) between bounces.
struct LineOffset {
  int64_t u = 0, v = 0;
};

class DiscreteLineSweep {
 public:
  DiscreteLineSweep(const VoxelGrid& grid, const SweepSettings& settings);
  // One per solve: it holds the line table and each thread's deferred light, too big to copy.
  DiscreteLineSweep(const DiscreteLineSweep&) = delete;
  DiscreteLineSweep& operator=(const DiscreteLineSweep&) = delete;

  /// A voxel as a look meets it, 16 bytes: a single side (its plane n.x = d with n in snorm16,
  /// its radiosity in half floats), or, with a zero normal, a cell of several sides whose index
  /// is stored in `offset`'s bits and which is looked up in the grid.
  struct Slot {
    int16_t normal[3];
    uint16_t radiosity[3];
    float offset;
  };
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
  /// An upper bound of a direction's line count over the directions `steps` and any LineOffset,
  /// and the bytes a sweep of `grid` holds for directions of that many lines, known before it is
  /// built.
  static size_t maxLineCount(const VoxelGrid& grid, std::span<const IVec3> steps);
  /// Throws InputError when a direction of `lines` lines is more than the sweep can number
  /// (line indices are 32-bit): a grid whose box is very large in voxels, however few it holds.
  static void checkLineCount(const VoxelGrid& grid, size_t lines);
  static size_t workingBytesFor(const VoxelGrid& grid, size_t lines) {
    const size_t threads = threadCount();
    const size_t bandBytes = threads > 1 ? kMaxSamples * sizeof(SampleCell) : 0;
    return bandBytes + SideVisibility::maskBytesFor(grid) +
           threads * (bandLineCapacity(grid, lines) * sizeof(LineState) +
                      waitingCapacity(grid, bandLineCapacity(grid, lines)) * sizeof(WaitingSide) +
                      DeferredGathers::kCapacity * sizeof(DeferredGathers::Item));
  }

  /// The naive line of every cell for a direction (for tests): lines[cell].
  std::vector<uint32_t> lineOfEachCell(const IVec3& step, const LineOffset& offset = {});
  /// Cells in the order a pass along `step` visits them (for tests).
  std::vector<uint32_t> passOrder(const IVec3& step);
  /// The same pass cut into `bands` bands of lines, or more where a band would hold more than
  /// bandLineLimit() lines: the cells each visits, in order.
  std::vector<std::vector<uint32_t>> passOrderInBands(const IVec3& step, size_t bands);
  /// The lines of the direction prepared last: line indices lie in [0, lineCount()).
  size_t lineCount() const { return lineCount_; }
  /// The most lines a band holds: each thread's records, sized for the widest direction yet.
  size_t bandLineLimit() const { return bandLines_; }
  /// Working memory of this sweep: each thread's line records, waiting sides and deferred
  /// light, the cells the bands are balanced on and the folds within cells and with neighbouring
  /// voxels.
  size_t workingBytes() const {
    size_t threads = 0;
    for (const BandScratch& scratch : scratch_)
      threads += scratch.lines.capacity() * sizeof(LineState) +
                 scratch.waiting.sides.capacity() * sizeof(WaitingSide) +
                 DeferredGathers::kCapacity * sizeof(DeferredGathers::Item);
    return threads + sampleCells_.capacity() * sizeof(SampleCell) + visibility_->foldBytes();
  }

 private:
  static constexpr uint32_t kCellRef = 0x80000000u;
  static constexpr uint32_t kNoVoxel = 0xffffffffu;
  /// A waiting side's link: the next waiting entry in the low 29 bits (kNoPending ends the
  /// chain), kSameRun when that entry is the voxel before it in the same run (one plane: the
  /// answer for one serves both), and in the top two the voxels it has looked through so far.
  static constexpr uint32_t kNoPending = 0x1fffffffu;
  static constexpr uint32_t kSameRun = 0x20000000u;
  static constexpr uint32_t kDepthShift = 30;
  static constexpr uint32_t kLookThrough = 2;
  /// The line's most recent voxel as its record keeps it: a side's packed normal and radiosity
  /// with its centroid (which the side, when it waits for light from ahead, looks from), or a
  /// zero normal for a cell of several sides.
  struct RecentVoxel {
    int16_t normal[3];
    uint16_t radiosity[3];
    Vec3 centroid;
  };
  /// 64 bytes per line, one cache line: its last voxel (runs along the same planes collapsed to
  /// their nearest voxel) inline, the two voxels before it by reference (an entry,
  /// kCellRef | cell, or kNoVoxel) and the nearer of them also as a slot, and the sides waiting
  /// on it, so that a visit mostly touches this record and the visited cell's own data only.
  /// The slot serves the sides that look past a grazed voxel, a tenth of the visits and most of
  /// a run's along a wall, which otherwise read a side visited long ago (cache misses).
  struct alignas(64) LineState {
    uint16_t stamp = 0;
    int16_t lastDominant = 0;
    uint32_t recentRef = kNoVoxel;
    uint32_t olderRef[2] = {kNoVoxel, kNoVoxel};
    /// The sides waiting for light from ahead: the first, and its link (the rest are chained
    /// through the band's WaitingSide list), so that a lone waiting side costs no access beyond
    /// this record.
    uint32_t pending = kNoPending, pendingLink = kNoPending;
    RecentVoxel recent;
    Slot older;  ///< olderRef[0] as a look meets it
  };
  static_assert(sizeof(LineState) == 64);
  /// The slot standing for a cell of several sides (zero normal, the cell's index in `offset`).
  static Slot cellSlot(uint32_t cell);
  /// Makes `ref` (an entry or kCellRef | cell) the line's recent voxel, pushing the one before
  /// back unless the run continues; the caller has set `older` to that voxel's slot and then
  /// writes the new recent voxel's data.
  static void becomeRecent(LineState& state, uint32_t ref, int32_t dominant, bool continues);
  /// The recent voxel as a slot (the cell's index for a cell of several sides).
  static Slot recentSlot(const LineState& state);

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
  };
  static void layoutLines(const IVec3& dims, const IVec3& step, const LineOffset& offset,
                          LineLayout& layout);
  void prepareLines(const IVec3& step, const LineOffset& offset = {});
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
  static constexpr size_t kBandShareOfLines = 24;
  /// In a box mostly empty (objects far apart), lines far outnumber sides: there a band holds at
  /// most a line per kSidesPerLine sides, so that the records take at most 8 B per side a thread
  /// and the sweep's memory grows with the sides, not with the box's cross-section. Two 1 m cubes
  /// 100 m apart with a lamp between (400k voxels, R = 8, 2 threads): 245 -> 82.5 B per side,
  /// peak 114 -> 47 MB, the sweeps 3.26 -> 2.32 s (the passes skip the empty slabs, which every
  /// band walked before). Four cubes at the corners of a 100 m square (200k voxels): 2,254 ->
  /// 88.5 B per side, peak 478 -> 31 MB, the sweeps 1.9-2.1 -> 2.2 s (3.3 s before a band skipped
  /// the slabs whose rows all lie outside it without a search). In a room a twenty-fourth of the
  /// lines is the smaller.
  static constexpr size_t kSidesPerLine = 8;
  static size_t bandLineCapacity(const VoxelGrid& grid, size_t lines) {
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
  static size_t bandCountFor(size_t threads, bool zDominant) {
    return threads > 1 ? (zDominant ? 2 : 16) * threads : 1;
  }
  /// Cuts the line table's rows into `count` bands of about equal numbers of cells (counted on
  /// a sample of the cells), and those holding more lines than bandLines_ further.
  void cutBands(size_t count);
  /// The index of row U's first line (U = the row count: the line count).
  uint32_t rowFirstLine(size_t row) const;
  /// The sample the bands are balanced on, made when first needed.
  void prepareBands();
  /// Light for sides that waited on a line: added to their accumulators in batches, after the
  /// fact, so that the sweep never stalls on a side it visited long ago.
  struct DeferredGathers {
    static constexpr uint32_t kCapacity = 4096;
    struct Item {
      uint32_t entry;
      Color light;
    };
    std::vector<Item> items = std::vector<Item>(kCapacity);
    uint32_t count = 0;
    void addTo(Color* gathered);
  };
  /// A side waiting on a line behind the first (which the line's record holds): its entry and
  /// its link (the next waiting side's place in the band's list, or kNoPending).
  struct WaitingSide {
    uint32_t entry, link;
  };
  /// Places for waiting sides a thread holds from the start for bands of `lines` lines, or for
  /// half the sides where they are fewer (a side faces ahead along one of s and -s): where more
  /// wait at once (long runs along a wall), the list grows and the sweep's bytes count it.
  /// Measured on room:16, R = 38, the most at once in a band: 4.4 a line at 2M voxels (two
  /// threads), 3.8 at 100k, 7.7 at 5,000 (one thread).
  static constexpr size_t kWaitingPerLine = 8, kWaitingFloor = 1024;
  static size_t waitingCapacity(const VoxelGrid& grid, size_t lines) {
    return std::min(kWaitingPerLine * lines, grid.entryCount() / 2) + kWaitingFloor;
  }
  /// The band's waiting sides: a place is taken when a side joins a line's chain and given
  /// back when the chain is answered, so that the list holds as many as wait at once (a place
  /// given back is the next taken, still in the cache). Free places are chained by `link`.
  struct WaitingList {
    std::vector<WaitingSide> sides;
    uint32_t free = kNoPending;
    void clear() {
      sides.clear();
      free = kNoPending;
    }
    uint32_t take(uint32_t entry, uint32_t link) {
      if (free == kNoPending) {
        sides.push_back({entry, link});
        return uint32_t(sides.size() - 1);
      }
      const uint32_t place = free;
      free = sides[place].link;
      sides[place] = {entry, link};
      return place;
    }
    WaitingSide giveBack(uint32_t place) {
      const WaitingSide side = sides[place];
      sides[place].link = free;
      free = place;
      return side;
    }
  };
  /// A thread's own: the records of the band it sweeps (line firstLine + i at i), reused from
  /// band to band, their pass stamp, its deferred light and the band's waiting sides (joining a
  /// chain writes to a place in this list, not beside a side visited long ago).
  struct BandScratch {
    std::vector<LineState> lines;
    uint16_t stamp = 0;
    DeferredGathers later;
    WaitingList waiting;
    /// Records for a band of `count` lines (room for `capacity`, the most a band holds), none of
    /// them holding an earlier pass's voxels; with them, the places for the waiting sides of
    /// `grid`'s bands.
    LineState* recordsFor(const VoxelGrid& grid, size_t count, size_t capacity);
  };
  template <bool kTangentCorrection>
  void pass(const IVec3& step, const LineBand& band, const Vec3& unit, float weight,
            const Source& source, std::span<Color> gathered, BandScratch& scratch);
  /// What a pass reads and writes, as raw pointers the compiler can keep in registers.
  struct PassView {
    const uint32_t* entryBegin;
    const PackedPoint* centroid;
    Vec3 pointOrigin;
    float pointStep;
    Source source;
    Color* gathered;
    WaitingList* waiting;
    DeferredGathers* later;
    Vec3 unit;
    float weight, tolerance, edge;
  };
  /// Lets a cell's sides look back along the line, then makes the cell the line's recent voxel.
  template <bool kTangentCorrection>
  void visitSingleSide(const PassView& view, uint32_t e, LineState& state, int32_t dominant) const;
  template <bool kTangentCorrection>
  void visitSeveralSides(const PassView& view, uint32_t cell, LineState& state,
                         int32_t dominant) const;
  /// Lets the sides waiting on the line's record look at the voxel in `slot` (whose centroid is
  /// `slotCentroid` when it holds one side).
  template <bool kTangentCorrection>
  void resolvePending(const PassView& view, LineState& state, const Slot& slot,
                      const Vec3& slotCentroid) const;
  /// What a side (its centroid, passed, not looked up: the side may have been visited long ago,
  /// and the caller holds it; its normal, which `normal()` gives) sees in slot s, whose centroid
  /// `slotCentroid()` gives when it holds one side; `light` gets the source's radiosity when it
  /// is Source. The two are called only when needed: when a back is met, or s holds a cell.
  template <typename Normal, typename SlotCentroid>
  Sight look(const PassView& view, const Vec3& centroid, const Normal& normal, const Slot& s,
             const Vec3& unit, Color& light, const SlotCentroid& slotCentroid) const;
  /// What a side sees past the line's recent voxel (the two voxels before it).
  Sight lookOlder(const PassView& view, const Vec3& centroid, const Vec3& normal,
                  const LineState& state, Color& light) const;
  /// Queues light for side e (a side that waited) in the pass's deferred batch.
  static void gatherLater(const PassView& view, uint32_t e, const Color& light);
  /// Makes side e wait on the line for light from ahead; `sameRun` when the side waiting before
  /// it is the previous voxel of its run.
  static void wait(const PassView& view, LineState& state, uint32_t e, bool sameRun);
  /// Calls f(cell, line, dominant) for every cell whose line lies in `band`, in the order of a
  /// pass along `step`: the grid's slabs, rows and cells, each run with the sign of its axis
  /// (inlined into the pass: called, its ring would live in memory).
  template <typename F>
  [[gnu::always_inline]] inline void forEachCellInPassOrder(const IVec3& step, const LineBand& band,
                                                            F&& f) const;
  /// The cells of one band of the direction prepared last, in pass order (for tests).
  std::vector<uint32_t> cellsInPassOrder(const IVec3& step, const LineBand& band) const;
  /// The rows of slab x whose lines lie in the band (x or y dominant).
  [[gnu::noinline]] std::pair<uint32_t, uint32_t> rowsInBand(uint32_t x,
                                                             const LineBand& band) const;
  /// The z of slab x whose lines lie in the band (z dominant): [first, second).
  [[gnu::noinline]] std::pair<uint32_t, uint32_t> zInBand(uint32_t x, const LineBand& band) const;

  const VoxelGrid& grid_;
  SweepSettings settings_;
  /// Read-only and the same for every direction: one for a sweep and all its copies (threads).
  std::shared_ptr<const SideVisibility> visibility_;
  /// Per axis: contribution to the line's (U, V) as U << 32 | V (the sum never carries).
  std::vector<uint64_t> lineTable_[3];
  std::vector<uint32_t> occupiedSlabs_;  ///< the x of the slabs that hold cells, ascending
  std::vector<int32_t> rowStart_;  ///< per U: the index of line (U, 0); rows hold only lines met
  std::vector<int32_t>
      dominantTable_[3];  ///< per axis: contribution to the signed dominant coordinate
  size_t lineCount_ = 0;  ///< this direction's
  size_t bandLines_ = 0;  ///< the most lines a band holds: its records' size
  tbb::enumerable_thread_specific<BandScratch> scratch_;
  std::vector<LineBand> bands_;  ///< this direction's
  /// The coordinates of every 32nd cell, or of 8,192 cells spread evenly over a larger grid:
  /// what the bands are balanced on (counted for every direction, so no more than that; made by
  /// prepareBands).
  static constexpr size_t kMaxSamples = 8192;
  using SampleCell = std::array<int16_t, 3>;
  std::vector<SampleCell> sampleCells_;
  std::vector<uint32_t> sampledPerRow_;  ///< per line table row, scratch for cutBands
  LineLayout layout_;                    ///< per-direction scratch, reused
};

}  // namespace rad
