#pragma once
// What a thread of the voxel sweep keeps while it sweeps a band of lines: a record per line (its
// last voxels and the sides waiting on it), the places of the sides waiting behind the first,
// and the light for waiting sides, added to their accumulators later; and the bytes they take.
//
// Each line keeps its last voxel (plane, radiosity, centroid) inline and the two before it by
// reference, so that the common case touches one line record and nothing else. Runs of voxels
// along the same planes are kept as one, so long grazing runs cost one slot.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "voxel/voxel_grid.h"

namespace rad::sweep {

/// A line record's references: a side (its entry), kCellRef | cell for a cell of several sides,
/// or kNoVoxel.
inline constexpr uint32_t kCellRef = 0x80000000u;
inline constexpr uint32_t kNoVoxel = 0xffffffffu;
/// A waiting side's link: the next waiting entry in the low 29 bits (kNoPending ends the
/// chain), kSameRun when that entry is the voxel before it in the same run (one plane: the
/// answer for one serves both), and in the top two the voxels it has looked through so far.
inline constexpr uint32_t kNoPending = 0x1fffffffu;
inline constexpr uint32_t kSameRun = 0x20000000u;
inline constexpr uint32_t kDepthShift = 30;
/// The most grazed voxels a look passes through (the tangent correction).
inline constexpr uint32_t kLookThrough = 2;

/// A voxel as a look meets it, 16 bytes: a single side (its plane n.x = d with n in snorm16,
/// its radiosity in half floats), or, with a zero normal, a cell of several sides whose index
/// is stored in `offset`'s bits and which is looked up in the grid.
struct Slot {
  int16_t normal[3];
  uint16_t radiosity[3];
  float offset;
};
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
  /// Bytes held: records, waiting places and deferred light.
  size_t bytes() const;
  /// Bytes a thread holds for bands of up to `bandLines` lines in `grid`, known beforehand.
  static size_t bytesFor(const VoxelGrid& grid, size_t bandLines);
};

}  // namespace rad::sweep
