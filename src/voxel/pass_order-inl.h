// The order a pass of the voxel sweep visits the cells of a band of lines in: a lexicographic
// order whose axes run with the direction's signs, walked directly on the grid's slabs, rows and
// cells (no sorting, no permutation arrays), meets each line's voxels in order along it.
//
// Compiled with the pass for every instruction set (sweep_pass.cpp), because the pass's visit
// is inlined into it as a lambda, which a function compiled for a narrower instruction set may
// not inline; the test hooks (discrete_line_sweep_orders.cpp) take the build's own.

// Highway's per-target include guard: this file is compiled once for every target.
#if defined(RADIOSITY_VOXEL_PASS_ORDER_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RADIOSITY_VOXEL_PASS_ORDER_INL_H_
#undef RADIOSITY_VOXEL_PASS_ORDER_INL_H_
#else
#define RADIOSITY_VOXEL_PASS_ORDER_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <cstdint>
#include <tuple>
#include <utility>

#include "voxel/line_bands.h"
#include "voxel/sweep_pass.h"

HWY_BEFORE_NAMESPACE();
namespace rad::sweep::HWY_NAMESPACE {

// Calls f(i) for i in [begin, end), ascending or descending. One call site, so that the nested
// loops of a pass inline into one body instead of eight copies of the innermost one.
template <typename F>
inline void forEach(uint32_t begin, uint32_t end, bool ascending, F&& f) {
  const uint32_t stride = ascending ? 1u : ~0u;  // -1 modulo 2^32
  uint32_t i = ascending ? begin : end - 1;
  for (uint32_t k = begin; k < end; ++k, i += stride) f(i);
}

// The indices of [range.first, range.second) whose row(i) lies in the band, for row(i)
// monotone in i (rising or falling): a subrange, found by two binary searches.
template <typename Row>
std::pair<uint32_t, uint32_t> withinBand(std::pair<uint32_t, uint32_t> range, const LineBand& band,
                                         Row&& row) {
  const uint32_t begin = range.first, end = range.second;
  if (begin == end) return range;
  const int64_t first = row(begin), last = row(end - 1);
  // Most ranges of a narrow band (a mostly empty box cuts many) lie wholly outside it.
  if (std::max(first, last) < band.uBegin || std::min(first, last) >= band.uEnd) return {end, end};
  const bool rising = first <= last;
  // The first index in [begin, end) whose row is past `bound` (before it when falling).
  auto firstPast = [&](int64_t bound) {
    uint32_t lo = begin, hi = end;
    while (lo < hi) {
      const uint32_t mid = lo + (hi - lo) / 2;
      if (rising ? row(mid) >= bound : row(mid) < bound)
        hi = mid;
      else
        lo = mid + 1;
    }
    return lo;
  };
  return rising ? std::pair(firstPast(band.uBegin), firstPast(band.uEnd))
                : std::pair(firstPast(band.uEnd), firstPast(band.uBegin));
}

// The cells of a row, [begin, end) sorted by z, whose z lies in [zs.first, zs.second). Most rows
// lie wholly inside or outside: two reads, no search.
inline std::pair<uint32_t, uint32_t> cellsWithin(const int16_t* z, uint32_t begin, uint32_t end,
                                                 std::pair<uint32_t, uint32_t> zs) {
  const int16_t low = int16_t(zs.first), high = int16_t(zs.second);
  if (z[begin] >= low && z[end - 1] < high) return {begin, end};
  if (z[end - 1] < low || z[begin] >= high) return {end, end};
  return {uint32_t(std::lower_bound(z + begin, z + end, low) - z),
          uint32_t(std::lower_bound(z + begin, z + end, high) - z)};
}

/// The rows of slab x whose lines lie in the band (x or y dominant).
[[gnu::noinline]] inline std::pair<uint32_t, uint32_t> rowsInBand(const PassCells& cells,
                                                                  uint32_t x,
                                                                  const LineBand& band) {
  const VoxelGrid& grid = cells.grid;
  const LineTable& table = cells.table;
  return withinBand({grid.slabRowBegin[x], grid.slabRowBegin[x + 1]}, band, [&](uint32_t row) {
    return int64_t((table.uv[0][x] + table.uv[1][size_t(grid.rowY[row])]) >> 32);
  });
}

/// The z of slab x whose lines lie in the band (z dominant): [first, second).
[[gnu::noinline]] inline std::pair<uint32_t, uint32_t> zInBand(const PassCells& cells, uint32_t x,
                                                               const LineBand& band) {
  const LineTable& table = cells.table;
  return withinBand({0u, uint32_t(cells.grid.dims.z)}, band,
                    [&](uint32_t z) { return int64_t((table.uv[0][x] + table.uv[2][z]) >> 32); });
}

/// Calls f(cell, line, dominant) for every cell whose line lies in `band`, in the order of a
/// pass along `step`: the grid's slabs, rows and cells, each run with the sign of its axis
/// (inlined into the pass: called, its ring would live in memory).
template <typename F>
[[gnu::always_inline]] inline void forEachCellInPassOrder(const PassCells& cells, const IVec3& step,
                                                          const LineBand& band, F&& f) {
  // A line's row U depends on the dominant coordinate and the outer of the other two
  // (LineLayout): on x and y for a dominant x or y, so that a band is a range of each slab's
  // rows; on x and z for a dominant z, so that a band is a range of z, which cuts each row.
  const VoxelGrid& grid = cells.grid;
  const LineTable& table = cells.table;
  const bool whole = band.holdsAll(table.rowCount());
  const bool zDominant = table.zDominant();
  const bool cutRows = !whole && zDominant;
  const int16_t* const cellZ = grid.cellZ.data();
  const uint32_t* const slabs = cells.occupiedSlabs.data();
  forEach(0, uint32_t(cells.occupiedSlabs.size()), step.x >= 0, [&](uint32_t k) {
    const uint32_t x = slabs[k];
    const uint64_t slabLine = table.uv[0][x];
    const int32_t slabDominant = table.dominant[0][x];
    const auto rows = whole || cutRows ? std::pair(grid.slabRowBegin[x], grid.slabRowBegin[x + 1])
                                       : rowsInBand(cells, x, band);
    const auto zs = cutRows ? zInBand(cells, x, band) : std::pair(0u, uint32_t(grid.dims.z));
    if (zs.first == zs.second) return;  // near the z axis, a band's lines cross few slabs
    forEach(rows.first, rows.second, step.y >= 0, [&](uint32_t row) {
      auto [begin, end] = std::pair(grid.rowCellBegin[row], grid.rowCellBegin[row + 1]);
      if (cutRows) std::tie(begin, end) = cellsWithin(cellZ, begin, end, zs);
      if (begin == end) return;
      const size_t y = size_t(grid.rowY[row]);
      const uint64_t rowLine = slabLine + table.uv[1][y];
      const int32_t rowDominant = slabDominant + table.dominant[1][y];
      if (zDominant) {
        forEach(begin, end, step.z >= 0, [&](uint32_t cell) {
          const size_t z = size_t(cellZ[cell]);
          const uint64_t uv = rowLine + table.uv[2][z];
          f(cell, uint32_t(table.rowStart[uv >> 32] + int32_t(uint32_t(uv))),
            rowDominant + table.dominant[2][z]);
        });
        return;
      }
      // Along a row of a dominant x or y only V moves (z's U and dominant parts are 0): the
      // row's lines start at one index.
      const int32_t rowFirst = table.rowStart[rowLine >> 32] + int32_t(uint32_t(rowLine));
      const uint64_t* const inner = table.uv[2].data();
      forEach(begin, end, step.z >= 0, [&](uint32_t cell) {
        f(cell, uint32_t(rowFirst + int32_t(uint32_t(inner[cellZ[cell]]))), rowDominant);
      });
    });
  });
}

}  // namespace rad::sweep::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // RADIOSITY_VOXEL_PASS_ORDER_INL_H_
