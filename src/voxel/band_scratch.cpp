#include "voxel/band_scratch.h"

#include <algorithm>

namespace rad::sweep {

namespace {

/// Places for waiting sides a thread holds from the start for bands of `lines` lines, or for
/// half the sides where they are fewer (a side faces ahead along one of s and -s): where more
/// wait at once (long runs along a wall), the list grows and the sweep's bytes count it.
/// Measured on room:16, R = 38, the most at once in a band: 4.4 a line at 2M voxels (two
/// threads), 3.8 at 100k, 7.7 at 5,000 (one thread).
constexpr size_t kWaitingPerLine = 8, kWaitingFloor = 1024;
size_t waitingCapacity(const VoxelGrid& grid, size_t lines) {
  return std::min(kWaitingPerLine * lines, grid.entryCount() / 2) + kWaitingFloor;
}

}  // namespace

void DeferredGathers::addTo(Color* gathered) {
  // The sides were visited long ago: fetch ahead so that the misses overlap.
  constexpr uint32_t kAhead = 16;
  for (uint32_t i = 0; i < count; ++i) {
    if (i + kAhead < count) __builtin_prefetch(&gathered[items[i + kAhead].entry], 1);
    gathered[items[i].entry] += items[i].light;
  }
  count = 0;
}

LineState* BandScratch::recordsFor(const VoxelGrid& grid, size_t count, size_t capacity) {
  if (lines.size() < count) {
    lines = std::vector<LineState>(std::max(count, capacity));
    waiting.sides.reserve(waitingCapacity(grid, lines.size()));
    stamp = 0;
  }
  // The 16-bit pass stamp tells this pass's records from older ones; when it wraps, the records
  // are cleared once (every 65,535 passes).
  if (++stamp == 0) {
    for (LineState& line : lines) line.stamp = 0;
    stamp = 1;
  }
  return lines.data();
}

size_t BandScratch::bytes() const {
  return lines.capacity() * sizeof(LineState) + waiting.sides.capacity() * sizeof(WaitingSide) +
         DeferredGathers::kCapacity * sizeof(DeferredGathers::Item);
}

size_t BandScratch::bytesFor(const VoxelGrid& grid, size_t bandLines) {
  return bandLines * sizeof(LineState) + waitingCapacity(grid, bandLines) * sizeof(WaitingSide) +
         DeferredGathers::kCapacity * sizeof(DeferredGathers::Item);
}

}  // namespace rad::sweep
