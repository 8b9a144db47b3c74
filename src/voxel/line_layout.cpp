#include "voxel/line_layout.h"

#include <fmt/format.h>
#include <radiosity/error.h>

#include <algorithm>
#include <cstdlib>
#include <utility>

namespace rad {

namespace {

int64_t floorDiv(int64_t n, int64_t d) {
  return n >= 0 ? n / d : -((-n + d - 1) / d);
}
int64_t ceilDiv(int64_t n, int64_t d) {
  return -floorDiv(-n, d);
}

// The axes by decreasing |component| of a step: d[0] dominant (ties keep axis order).
std::array<int, 3> axesByMagnitude(const IVec3& step) {
  std::array<int, 3> d{0, 1, 2};
  std::stable_sort(d.begin(), d.end(),
                   [&](int i, int j) { return std::abs(step[i]) > std::abs(step[j]); });
  return d;
}

}  // namespace

void LineLayout::layOut(const IVec3& dims, const IVec3& step, const LineOffset& offset) {
  // The dominant component a after signing; the other two, b and c, in either order (the lines
  // are the same). A row of the table holds the lines of one U, so V is taken along the
  // innermost axis a pass walks (z, or y when z is dominant): the cells of a row then meet line
  // records that lie side by side, not a row of the table apart.
  std::array<int, 3> d = axesByMagnitude(step);
  // The offsets stay with their axes (u shifts the one of component b): same lines either way.
  const int inner = d[0] == 2 ? 1 : 2;
  const bool swapped = d[1] == inner;
  if (swapped) std::swap(d[1], d[2]);
  const int64_t shiftU = swapped ? offset.v : offset.u, shiftV = swapped ? offset.u : offset.v;
  axes = d;
  const int64_t a = std::abs(step[d[0]]), b = std::abs(step[d[1]]), c = std::abs(step[d[2]]);
  for (int k = 0; k < 3; ++k) {
    const int64_t sign = step[d[k]] >= 0 ? 1 : -1;
    std::vector<int64_t>& uk = u[size_t(k)];
    std::vector<int64_t>& vk = v[size_t(k)];
    uk.resize(size_t(dims[d[k]]));
    vk.resize(uk.size());
    for (size_t t = 0; t < uk.size(); ++t) {
      const int64_t m = sign * int64_t(t);  // coordinate in the frame where the step is positive
      // floor((a y - b x + u) / a) = y - ceil((b x - u) / a), likewise for z.
      uk[t] = k == 0 ? -ceilDiv(b * m - shiftU, a) : (k == 1 ? m : 0);
      vk[t] = k == 0 ? -ceilDiv(c * m - shiftV, a) : (k == 2 ? m : 0);
    }
    const int64_t uMin = *std::min_element(uk.begin(), uk.end());
    const int64_t vMin = *std::min_element(vk.begin(), vk.end());
    for (size_t t = 0; t < uk.size(); ++t) uk[t] -= uMin, vk[t] -= vMin;
  }
  // Along the dominant axis the shear (u[0], v[0]) moves monotonically, by at most 1 per step:
  // the t0 whose rows [u0, u0 + D1) cover U form one run, whose ends hold the extreme v0.
  const std::vector<int64_t>& u0 = u[0];
  const std::vector<int64_t>& v0 = v[0];
  const int64_t d1 = dims[d[1]], d2 = dims[d[2]], n0 = int64_t(u0.size());
  const bool rising = u0.front() <= u0.back();
  auto at = [&](int64_t i) { return size_t(rising ? i : n0 - 1 - i); };  // u0 non-decreasing in i
  const int64_t uCount = *std::max_element(u0.begin(), u0.end()) + d1;
  vLow.resize(size_t(uCount));
  vHigh.resize(size_t(uCount));
  int64_t first = 0, last = 0;  // the covering run [first, last] in i
  for (int64_t row = 0; row < uCount; ++row) {
    while (u0[at(first)] < row - d1 + 1) ++first;
    while (last + 1 < n0 && u0[at(last + 1)] <= row) ++last;
    const int64_t va = v0[at(first)], vb = v0[at(last)];
    vLow[size_t(row)] = std::min(va, vb);
    vHigh[size_t(row)] = std::max(va, vb) + d2 - 1;
  }
}

void LineTable::prepare(const VoxelGrid& grid, const IVec3& step, const LineOffset& offset) {
  layout.layOut(grid.dims, step, offset);
  for (int k = 0; k < 3; ++k) {
    const int axis = layout.axes[size_t(k)];
    const int64_t sign = step[axis] >= 0 ? 1 : -1;
    const std::vector<int64_t>& u = layout.u[size_t(k)];
    const std::vector<int64_t>& v = layout.v[size_t(k)];
    uv[axis].resize(u.size());
    dominant[axis].resize(u.size());
    for (size_t t = 0; t < u.size(); ++t) {
      uv[axis][t] = uint64_t(u[t]) << 32 | uint64_t(v[t]);
      dominant[axis][t] = k == 0 ? int32_t(sign * int64_t(t)) : 0;
    }
  }
  // Row U's lines follow row U - 1's: line = rowStart[U] + V (row starts past 32 bits are
  // never used: the count is checked just below, before a sweep reads them).
  rowStart.resize(layout.vLow.size());
  int64_t lines = 0;
  for (size_t row = 0; row < rowStart.size(); ++row) {
    rowStart[row] = int32_t(lines - layout.vLow[row]);
    lines += layout.vHigh[row] - layout.vLow[row] + 1;
  }
  checkLineCount(grid, size_t(lines));
  lineCount_ = size_t(lines);
}

void checkLineCount(const VoxelGrid& grid, size_t lines) {
  // rowStart holds a row's first line less its lowest V, signed: 2^31 - 1 lines at most.
  constexpr size_t kMostLines = size_t(INT32_MAX);
  if (lines > kMostLines)
    throw InputError(
        "voxel grid",
        fmt::format("{} lines cross the grid's {} x {} x {} voxels along one direction, "
                    "more than the sweep's limit of {}; use a larger voxel size",
                    lines, grid.dims.x, grid.dims.y, grid.dims.z, kMostLines));
}

size_t maxLineCount(const VoxelGrid& grid, std::span<const IVec3> steps) {
  // A line offset moves each dominant-axis shear by 0 or 1 in U and in V: every shifted layout
  // lies in the unshifted one grown by one row and one column, whose row ranges bound it.
  LineLayout layout;
  size_t most = 0;
  for (const IVec3& step : steps) {
    layout.layOut(grid.dims, step, {});
    const size_t rows = layout.vLow.size();
    size_t count = 0;
    for (size_t row = 0; row <= rows; ++row) {
      const size_t here = std::min(row, rows - 1), below = row == 0 ? 0 : row - 1;
      const int64_t low = std::min(layout.vLow[here], layout.vLow[below]);
      const int64_t high = std::max(layout.vHigh[here], layout.vHigh[below]) + 1;
      count += size_t(high - low + 1);
    }
    most = std::max(most, count);
  }
  return most;
}

}  // namespace rad
