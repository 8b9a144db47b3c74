#include "voxel/discrete_line_sweep.h"

#include <fmt/format.h>
#include <immintrin.h>
#include <radiosity/error.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>

#include "voxel/half_colors.h"
#include "voxel/half_float.h"

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
template <typename Band, typename Row>
std::pair<uint32_t, uint32_t> withinBand(std::pair<uint32_t, uint32_t> range, const Band& band,
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

}  // namespace

DiscreteLineSweep::DiscreteLineSweep(const VoxelGrid& grid, const SweepSettings& settings)
    : grid_(grid), settings_(settings), visibility_(std::make_shared<const SideVisibility>(grid)) {
  for (uint32_t x = 0; x < uint32_t(grid.dims.x); ++x)
    if (grid.slabRowBegin[x] < grid.slabRowBegin[x + 1]) occupiedSlabs_.push_back(x);
  // A line's record holds its first waiting side as a 29-bit entry index.
  if (grid.entryCount() >= kNoPending)
    throw InputError("voxel grid", std::to_string(grid.entryCount()) +
                                       " voxel sides exceed the sweep's limit of " +
                                       std::to_string(kNoPending - 1) +
                                       "; use a larger voxel size");
}

void DiscreteLineSweep::prepareBands() {
  // Made on the first sweep with several bands: a single thread never reads it.
  if (!sampleCells_.empty() || grid_.cellCount() == 0) return;
  const VoxelGrid& grid = grid_;
  const size_t stride = std::max<size_t>(32, (grid.cellCount() + kMaxSamples - 1) / kMaxSamples);
  for (uint32_t x = 0; x < uint32_t(grid.dims.x); ++x)
    for (uint32_t row = grid.slabRowBegin[x]; row < grid.slabRowBegin[x + 1]; ++row)
      for (uint32_t cell = grid.rowCellBegin[row]; cell < grid.rowCellBegin[row + 1]; ++cell)
        if (cell % stride == 0)
          sampleCells_.push_back({int16_t(x), grid.rowY[row], grid.cellZ[cell]});
}

size_t DiscreteLineSweep::threadCount() {
  return std::min(size_t(std::max(1, tbb::this_task_arena::max_concurrency())),
                  tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

uint32_t DiscreteLineSweep::rowFirstLine(size_t row) const {
  return row < rowStart_.size() ? uint32_t(rowStart_[row] + layout_.vLow[row])
                                : uint32_t(lineCount_);
}

void DiscreteLineSweep::cutBands(size_t count) {
  bands_.clear();
  const size_t rows = rowStart_.size();
  std::vector<uint32_t>& perRow = sampledPerRow_;
  perRow.assign(rows, 0);
  if (count > 1) {
    prepareBands();
    for (const auto& [x, y, z] : sampleCells_)
      ++perRow[(lineTable_[0][size_t(x)] + lineTable_[1][size_t(y)] + lineTable_[2][size_t(z)]) >>
               32];
  }
  auto cut = [&](size_t begin, size_t end) {
    const uint32_t first = rowFirstLine(begin);
    bands_.push_back({int64_t(begin), int64_t(end), first, rowFirstLine(end) - first});
  };
  // Band k of the count ends at the first row where the running count reaches k / count of the
  // sample; a band ends earlier where its next row would take it past bandLines_ lines.
  const double total = double(sampleCells_.size());
  size_t begin = 0, quotas = 0;
  int64_t seen = 0;
  for (size_t row = 0; row < rows; ++row) {
    if (row > begin && rowFirstLine(row + 1) - rowFirstLine(begin) > bandLines_) {
      cut(begin, row);
      begin = row;
    }
    seen += perRow[row];
    if (quotas + 1 < count && double(seen) >= total * double(quotas + 1) / double(count)) {
      ++quotas;
      cut(begin, row + 1);
      begin = row + 1;
    }
  }
  if (begin < rows || bands_.empty()) cut(begin, rows);
}

void DiscreteLineSweep::layoutLines(const IVec3& dims, const IVec3& step, const LineOffset& offset,
                                    LineLayout& layout) {
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
  layout.axes = d;
  const int64_t a = std::abs(step[d[0]]), b = std::abs(step[d[1]]), c = std::abs(step[d[2]]);
  for (int k = 0; k < 3; ++k) {
    const int64_t sign = step[d[k]] >= 0 ? 1 : -1;
    std::vector<int64_t>& u = layout.u[size_t(k)];
    std::vector<int64_t>& v = layout.v[size_t(k)];
    u.resize(size_t(dims[d[k]]));
    v.resize(u.size());
    for (size_t t = 0; t < u.size(); ++t) {
      const int64_t m = sign * int64_t(t);  // coordinate in the frame where the step is positive
      // floor((a y - b x + u) / a) = y - ceil((b x - u) / a), likewise for z.
      u[t] = k == 0 ? -ceilDiv(b * m - shiftU, a) : (k == 1 ? m : 0);
      v[t] = k == 0 ? -ceilDiv(c * m - shiftV, a) : (k == 2 ? m : 0);
    }
    const int64_t uMin = *std::min_element(u.begin(), u.end());
    const int64_t vMin = *std::min_element(v.begin(), v.end());
    for (size_t t = 0; t < u.size(); ++t) u[t] -= uMin, v[t] -= vMin;
  }
  // Along the dominant axis the shear (u[0], v[0]) moves monotonically, by at most 1 per step:
  // the t0 whose rows [u0, u0 + D1) cover U form one run, whose ends hold the extreme v0.
  const std::vector<int64_t>& u0 = layout.u[0];
  const std::vector<int64_t>& v0 = layout.v[0];
  const int64_t d1 = dims[d[1]], d2 = dims[d[2]], n0 = int64_t(u0.size());
  const bool rising = u0.front() <= u0.back();
  auto at = [&](int64_t i) { return size_t(rising ? i : n0 - 1 - i); };  // u0 non-decreasing in i
  const int64_t uCount = *std::max_element(u0.begin(), u0.end()) + d1;
  layout.vLow.resize(size_t(uCount));
  layout.vHigh.resize(size_t(uCount));
  int64_t first = 0, last = 0;  // the covering run [first, last] in i
  for (int64_t row = 0; row < uCount; ++row) {
    while (u0[at(first)] < row - d1 + 1) ++first;
    while (last + 1 < n0 && u0[at(last + 1)] <= row) ++last;
    const int64_t va = v0[at(first)], vb = v0[at(last)];
    layout.vLow[size_t(row)] = std::min(va, vb);
    layout.vHigh[size_t(row)] = std::max(va, vb) + d2 - 1;
  }
}

void DiscreteLineSweep::prepareLines(const IVec3& step, const LineOffset& offset) {
  layoutLines(grid_.dims, step, offset, layout_);
  for (int k = 0; k < 3; ++k) {
    const int axis = layout_.axes[size_t(k)];
    const int64_t sign = step[axis] >= 0 ? 1 : -1;
    const std::vector<int64_t>& u = layout_.u[size_t(k)];
    const std::vector<int64_t>& v = layout_.v[size_t(k)];
    lineTable_[axis].resize(u.size());
    dominantTable_[axis].resize(u.size());
    for (size_t t = 0; t < u.size(); ++t) {
      lineTable_[axis][t] = uint64_t(u[t]) << 32 | uint64_t(v[t]);
      dominantTable_[axis][t] = k == 0 ? int32_t(sign * int64_t(t)) : 0;
    }
  }
  // Row U's lines follow row U - 1's: line = rowStart_[U] + V (row starts past 32 bits are
  // never used: the count is checked just below, before a sweep reads them).
  rowStart_.resize(layout_.vLow.size());
  int64_t lineCount = 0;
  for (size_t row = 0; row < rowStart_.size(); ++row) {
    rowStart_[row] = int32_t(lineCount - layout_.vLow[row]);
    lineCount += layout_.vHigh[row] - layout_.vLow[row] + 1;
  }
  checkLineCount(grid_, size_t(lineCount));
  lineCount_ = size_t(lineCount);
  // Without a reservation (a sweep of a single direction), bands are sized for this one.
  reserveLines(lineCount_);
}

DiscreteLineSweep::LineState* DiscreteLineSweep::BandScratch::recordsFor(const VoxelGrid& grid,
                                                                         size_t count,
                                                                         size_t capacity) {
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

void DiscreteLineSweep::checkLineCount(const VoxelGrid& grid, size_t lines) {
  // rowStart_ holds a row's first line less its lowest V, signed: 2^31 - 1 lines at most.
  constexpr size_t kMostLines = size_t(INT32_MAX);
  if (lines > kMostLines)
    throw InputError(
        "voxel grid",
        fmt::format("{} lines cross the grid's {} x {} x {} voxels along one direction, "
                    "more than the sweep's limit of {}; use a larger voxel size",
                    lines, grid.dims.x, grid.dims.y, grid.dims.z, kMostLines));
}

size_t DiscreteLineSweep::maxLineCount(const VoxelGrid& grid, std::span<const IVec3> steps) {
  // A line offset moves each dominant-axis shear by 0 or 1 in U and in V: every shifted layout
  // lies in the unshifted one grown by one row and one column, whose row ranges bound it.
  LineLayout layout;
  size_t most = 0;
  for (const IVec3& step : steps) {
    layoutLines(grid.dims, step, {}, layout);
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

namespace {

bool holdsCell(const int16_t normal[3]) {
  return (normal[0] | normal[1] | normal[2]) == 0;
}

// A packed normal and radiosity (a Slot's or a RecentVoxel's first 12 bytes, a SideOrientation)
// decode with one 8-byte load and one conversion each; the fourth lane, read from the field
// after, is dropped.
Vec3 lanes(__m128 v) {
  alignas(16) float f[4];
  _mm_store_ps(f, v);
  return Vec3(f[0], f[1], f[2]);
}

__m128i eightBytesAt(const void* p) {
  int64_t bits;
  std::memcpy(&bits, p, sizeof bits);
  return _mm_cvtsi64_si128(bits);
}

template <typename Packed>
Vec3 slotNormal(const Packed& p) {
  static_assert(offsetof(Packed, normal) == 0 && sizeof(Packed) >= 8);
  const __m128 n = _mm_cvtepi32_ps(_mm_cvtepi16_epi32(eightBytesAt(&p)));
  return lanes(_mm_mul_ps(n, _mm_set1_ps(1.0f / PackedNormal::kScale)));
}

template <typename Packed>
Color halfColor(const Packed& p) {
  return lanes(
      _mm_cvtph_ps(eightBytesAt(reinterpret_cast<const char*>(&p) + offsetof(Packed, radiosity))));
}

// Side e's unit normal and the radiosity it sends (over the Source's scale), read from the
// Source's arrays (a SentLight's 6 bytes as 4 + 2: its array ends where its last side does).
Vec3 sideNormal(const DiscreteLineSweep::Source& source, size_t e) {
  return slotNormal(source.normals[e]);
}
// The three half floats in the low 16-bit lanes, the others zero.
__m128i sentHalves(const DiscreteLineSweep::Source& source, size_t e) {
  uint32_t low;
  uint16_t high;
  std::memcpy(&low, source.sides[e].radiosity, sizeof low);
  std::memcpy(&high, source.sides[e].radiosity + 2, sizeof high);
  return _mm_insert_epi16(_mm_cvtsi32_si128(int(low)), high, 2);
}
Color sideLight(const DiscreteLineSweep::Source& source, size_t e) {
  return lanes(_mm_cvtph_ps(sentHalves(source, e)));
}
// A slot from its normal and radiosity (`packed`'s first 12 bytes) and its offset, put together
// in one register: kept in memory it is one store, from which a look's 8-byte reads of normal
// and radiosity are served at once (written field by field, each such read waited for the
// stores to reach the cache).
DiscreteLineSweep::Slot slotOf(__m128i packed, float offset) {
  const __m128i v = _mm_insert_epi32(packed, std::bit_cast<int>(offset), 3);
  DiscreteLineSweep::Slot slot;
  std::memcpy(&slot, &v, sizeof slot);
  return slot;
}

// Side e, whose centroid is c, as a look meets it: its plane and the radiosity it sends.
DiscreteLineSweep::Slot sideSlot(const DiscreteLineSweep::Source& source, size_t e, const Vec3& c) {
  static_assert(offsetof(DiscreteLineSweep::Slot, radiosity) == 6 &&
                offsetof(DiscreteLineSweep::Slot, offset) == 12);
  // The normal in 16-bit lanes 0-2, the radiosity moved up into lanes 3-5.
  const __m128i normal = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(&source.normals[e]));
  const __m128i packed = _mm_blend_epi16(normal, _mm_slli_si128(sentHalves(source, e), 6), 0x38);
  return slotOf(packed, glm::dot(slotNormal(source.normals[e]), c));
}

// Side e's centroid, as the grid's centroidOf gives it (its three fields shifted into three
// 64-bit lanes at once, their low halves converted and scaled with one FMA, as there).
template <typename View>
Vec3 centroidOf(const View& view, size_t e) {
  constexpr int64_t kMask = (int64_t(1) << 21) - 1;
  const __m256i bits = _mm256_set1_epi64x(int64_t(view.centroid[e].bits));
  const __m256i fields = _mm256_and_si256(_mm256_srlv_epi64(bits, _mm256_setr_epi64x(0, 21, 42, 0)),
                                          _mm256_set1_epi64x(kMask));
  const __m128i low = _mm256_castsi256_si128(
      _mm256_permutevar8x32_epi32(fields, _mm256_setr_epi32(0, 2, 4, 6, 0, 0, 0, 0)));
  // The origin and the step, one load: (x, y, z, step).
  static_assert(offsetof(View, pointStep) == offsetof(View, pointOrigin) + 3 * sizeof(float));
  const __m128 frame = _mm_loadu_ps(&view.pointOrigin.x);
  const __m128 step = _mm_shuffle_ps(frame, frame, _MM_SHUFFLE(3, 3, 3, 3));
  return lanes(_mm_fmadd_ps(_mm_cvtepi32_ps(low), step, frame));
}

uint32_t slotCell(float offset) {
  uint32_t cell;
  std::memcpy(&cell, &offset, sizeof cell);
  return cell;
}

}  // namespace

DiscreteLineSweep::Source DiscreteLineSweep::packSides(const VoxelGrid& grid,
                                                       const std::function<Color(size_t)>& sends,
                                                       std::span<SentLight> sides) {
  // A group's mean is at most its largest member: the largest side bounds every slot.
  const float scale = halfScaleFor(largestComponent(sides.size(), sends));
  const float inverse = 1.0f / scale;  // a power of two: exact
  for (size_t begin = 0; begin < sides.size();) {
    size_t end = begin + 1;
    while (end < sides.size() && grid.orientation[end].sharesPrevious) ++end;
    Color b = sends(begin);
    if (end - begin > 1) {
      Vec3d sum(0.0);
      double area = 0.0;
      for (size_t e = begin; e < end; ++e) {
        sum += double(grid.areaOf(e)) * Vec3d(e == begin ? b : sends(e));
        area += grid.areaOf(e);
      }
      if (area > 0.0) b = Color(sum / area);
    }
    b *= inverse;
    for (size_t e = begin; e < end; ++e)
      for (int k = 0; k < 3; ++k) sides[e].radiosity[k] = toHalf(b[k]);
    begin = end;
  }
  return {grid.orientation.data(), sides, scale};
}

inline DiscreteLineSweep::Slot DiscreteLineSweep::cellSlot(uint32_t cell) {
  Slot slot{};
  std::memcpy(&slot.offset, &cell, sizeof cell);
  return slot;
}

inline DiscreteLineSweep::Slot DiscreteLineSweep::recentSlot(const LineState& state) {
  if (holdsCell(state.recent.normal)) return cellSlot(state.recentRef & ~kCellRef);
  // The record's normal and radiosity lie as a slot's do.
  static_assert(offsetof(RecentVoxel, radiosity) == offsetof(Slot, radiosity));
  return slotOf(_mm_loadu_si128(reinterpret_cast<const __m128i*>(&state.recent)),
                glm::dot(slotNormal(state.recent), state.recent.centroid));
}

template <typename Normal, typename SlotCentroid>
inline Sight DiscreteLineSweep::look(const PassView& view, const Vec3& centroid,
                                     const Normal& normal, const Slot& s, const Vec3& unit,
                                     Color& light, const SlotCentroid& slotCentroid) const {
  if (holdsCell(s.normal)) {
    uint32_t side = 0;
    const Sight sight = visibility_->look(centroid, normal(), slotCell(s.offset), unit, side);
    if (sight == Sight::Source) light = sideLight(view.source, side);
    return sight;
  }
  const Vec3 n = slotNormal(s);
  const Sight sight =
      planeSight(glm::dot(n, centroid) - s.offset, glm::dot(n, unit), view.tolerance);
  if (sight == Sight::Source) light = halfColor(s);
  if (sight == Sight::Blocked && passesConvexEdge(normal(), centroid, slotCentroid(), view.edge))
    return Sight::Through;
  return sight;
}

template <bool kTangentCorrection>
inline void DiscreteLineSweep::visitSingleSide(const PassView& view, uint32_t e, LineState& state,
                                               int32_t dominant) const {
  // Most cells hold one side and most recent voxels are one side: the plane test against the
  // recent voxel serves the look back, the run test and the waiting sides, computed once.
  const Vec3 n = sideNormal(view.source, e);
  const Vec3 c = centroidOf(view, e);
  const float facing = glm::dot(n, view.unit);  // < 0: e looks back along the line, > 0: ahead
  const RecentVoxel& recent = state.recent;
  const bool hasRecent = state.recentRef != kNoVoxel;
  const bool recentIsSide = (state.recentRef & kCellRef) == 0;  // kNoVoxel has the bit too
  Vec3 recentNormal(0.0f);
  float height = 0.0f, recentFacing = 0.0f;
  bool inRecentPlane = false;
  if (recentIsSide) {
    recentNormal = slotNormal(recent);
    height = glm::dot(recentNormal, c - recent.centroid);
    recentFacing = glm::dot(recentNormal, view.unit);
    inRecentPlane = std::abs(height) <= view.tolerance;
  }
  // A run along the same plane stays one voxel: its nearest.
  const bool continues = kTangentCorrection && inRecentPlane &&
                         std::abs(dominant - state.lastDominant) == 1 &&
                         glm::dot(recentNormal, n) > kSamePlaneCos;
  if (!continues && state.pending != kNoPending) {
    // Most often the one side waiting is the recent voxel, a wall across the room: it looks at
    // e's plane from its centroid, which the record holds, unless it grazes e (then the
    // general rule lets it wait on).
    Sight recentSight = planeSight(glm::dot(n, recent.centroid - c), -facing, view.tolerance);
    if (recentSight == Sight::Blocked && recentIsSide &&
        passesConvexEdge(recentNormal, recent.centroid, c, view.edge))
      recentSight = Sight::Through;
    if (state.pending == state.recentRef && state.pendingLink == kNoPending && recentIsSide &&
        recentSight != Sight::Through) {
      if (recentSight == Sight::Source)
        gatherLater(view, state.pending, sideLight(view.source, e) * (recentFacing * view.weight));
      state.pending = kNoPending;
    } else {
      resolvePending<kTangentCorrection>(view, state, sideSlot(view.source, e, c), c);
    }
  }
  if (facing < 0.0f && hasRecent) {
    Color light(0.0f);
    Sight sight;
    if (recentIsSide) {
      sight = planeSight(height, recentFacing, view.tolerance);
      if (sight == Sight::Source) light = halfColor(recent);
      if (sight == Sight::Blocked && passesConvexEdge(n, c, recent.centroid, view.edge))
        sight = Sight::Through;
    } else {
      sight = look(
          view, c, [&] { return n; }, recentSlot(state), view.unit, light,
          [&] { return recent.centroid; });
    }
    if (kTangentCorrection && sight == Sight::Through) sight = lookOlder(view, c, n, state, light);
    if (sight == Sight::Source) view.gathered[e] += light * (-facing * view.weight);
  } else if (facing > 0.0f) {
    wait(view, state, e, continues && state.pending == state.recentRef);
  }
  if (!continues && hasRecent) {
    // The recent voxel becomes the older one: its slot, from the normal this visit already
    // converted (recentSlot would convert it again on every new run: 0.90x, measured).
    if (recentIsSide) {
      std::memcpy(&state.older, &recent, offsetof(Slot, offset));
      state.older.offset = glm::dot(recentNormal, recent.centroid);
    } else {
      state.older = cellSlot(state.recentRef & ~kCellRef);
    }
  }
  becomeRecent(state, e, dominant, continues);
  // The normal's eight bytes first: its spare lane lands where the radiosity goes.
  static_assert(offsetof(RecentVoxel, radiosity) == 6);
  std::memcpy(&state.recent, &view.source.normals[e], 8);
  std::memcpy(state.recent.radiosity, &view.source.sides[e], sizeof state.recent.radiosity);
  state.recent.centroid = c;
}

inline void DiscreteLineSweep::becomeRecent(LineState& state, uint32_t ref, int32_t dominant,
                                            bool continues) {
  // A run along the same planes stays one voxel (its nearest): only a new run pushes the
  // voxels before it back.
  if (!continues) {
    state.olderRef[1] = state.olderRef[0];
    state.olderRef[0] = state.recentRef;
  }
  state.recentRef = ref;
  state.lastDominant = int16_t(dominant);
}

inline void DiscreteLineSweep::wait(const PassView& view, LineState& state, uint32_t e,
                                    bool sameRun) {
  const uint32_t next = state.pending == kNoPending
                            ? kNoPending
                            : view.waiting->take(state.pending, state.pendingLink);
  state.pendingLink = next | (sameRun ? kSameRun : 0u);
  state.pending = e;
}

template <bool kTangentCorrection>
void DiscreteLineSweep::visitSeveralSides(const PassView& view, uint32_t cell, LineState& state,
                                          int32_t dominant) const {
  const Vec3& unit = view.unit;
  const Source& source = view.source;
  const Slot slot = cellSlot(cell);
  // A run of cells holding the same planes stays one voxel.
  const bool continues = kTangentCorrection && state.recentRef != kNoVoxel &&
                         std::abs(dominant - state.lastDominant) == 1 &&
                         holdsCell(state.recent.normal) &&
                         visibility_->continuesPlanes(cell, state.recentRef & ~kCellRef);
  if (!continues && state.pending != kNoPending)
    resolvePending<kTangentCorrection>(view, state, slot, Vec3(0.0f));  // a cell: no centroid
  const uint32_t begin = grid_.cellEntryBegin[cell], end = grid_.cellEntryBegin[cell + 1];
  const SideVisibility::CellFolds folds = visibility_->foldsOf(cell);
  const bool hasRecent = state.recentRef != kNoVoxel;
  const Slot recent = hasRecent ? recentSlot(state) : Slot{};  // what the sides facing back meet
  for (uint32_t e = begin; e < end; ++e) {
    const Vec3 normal = sideNormal(source, e);
    const float facing = glm::dot(normal, unit);
    if (facing == 0.0f) continue;
    const float w = std::abs(facing) * view.weight;
    // The cell's own other sides first (the faces of an inner edge see each other).
    uint32_t own = 0;
    if (folds.hasFold(e) &&
        visibility_->lookWithinCell(e, folds, facing < 0.0f ? unit : -unit, own)) {
      view.gathered[e] += sideLight(source, own) * w;
    } else if (facing > 0.0f) {
      wait(view, state, e, false);
    } else if (hasRecent) {
      Color light(0.0f);
      const Vec3 c = centroidOf(view, e);
      Sight sight = look(
          view, c, [&] { return normal; }, recent, unit, light,
          [&] { return state.recent.centroid; });
      if (kTangentCorrection && sight == Sight::Through)
        sight = lookOlder(view, c, normal, state, light);
      if (sight == Sight::Source) view.gathered[e] += light * w;
    }
  }
  if (!continues && hasRecent) state.older = recent;
  becomeRecent(state, kCellRef | cell, dominant, continues);
  state.recent.normal[0] = state.recent.normal[1] = state.recent.normal[2] = 0;
}

inline void DiscreteLineSweep::gatherLater(const PassView& view, uint32_t e, const Color& light) {
  // The side's accumulator is fetched now as well, up to a batch before it is added to: the
  // batch's fetches ahead alone leave part of the misses' wait (1.005-1.017x, one and two
  // threads, runs side by side).
  __builtin_prefetch(&view.gathered[e], 1);
  DeferredGathers& later = *view.later;
  later.items[later.count++] = {e, light};
  if (later.count == DeferredGathers::kCapacity) later.addTo(view.gathered);
}

void DiscreteLineSweep::DeferredGathers::addTo(Color* gathered) {
  // The sides were visited long ago: fetch ahead so that the misses overlap.
  constexpr uint32_t kAhead = 16;
  for (uint32_t i = 0; i < count; ++i) {
    if (i + kAhead < count) __builtin_prefetch(&gathered[items[i + kAhead].entry], 1);
    gathered[items[i].entry] += items[i].light;
  }
  count = 0;
}

template <bool kTangentCorrection>
void DiscreteLineSweep::resolvePending(const PassView& view, LineState& state, const Slot& slot,
                                       const Vec3& slotCentroid) const {
  // The sides waiting for light from ahead meet a new voxel (the nearest of its run): each sees
  // its source, is blocked, or, grazing it, waits for the next one (with the tangent correction,
  // up to kLookThrough voxels, as many as a look back passes). The first waiting side is often
  // the line's recent voxel, whose centroid the record holds.
  const Vec3 back = -view.unit;
  uint32_t m = state.pending, link = state.pendingLink;
  uint32_t waiting = kNoPending, waitingLink = kNoPending;
  Sight sight = Sight::Through;
  Color light(0.0f);
  float weight = 0.0f;
  bool sameRunAsBefore = false, keptBefore = false;
  while (true) {
    if (!sameRunAsBefore) {
      const bool recent = m == state.recentRef;
      const Vec3 centroid = recent ? state.recent.centroid : centroidOf(view, m);
      // The normal of a side visited long ago is read only when needed (a miss).
      const auto normal = [&] {
        return recent ? slotNormal(state.recent) : sideNormal(view.source, m);
      };
      sight = look(view, centroid, normal, slot, back, light, [&] { return slotCentroid; });
      if (sight == Sight::Source) weight = glm::dot(normal(), view.unit) * view.weight;
    }
    const uint32_t depth = link >> kDepthShift;
    if (sight == Sight::Source) {
      gatherLater(view, m, light * weight);
    } else if (kTangentCorrection && sight == Sight::Through && depth < kLookThrough) {
      // Kept, in reverse order: the run mark now links it to the side kept before it.
      const uint32_t next =
          waiting == kNoPending ? kNoPending : view.waiting->take(waiting, waitingLink);
      waitingLink =
          next | ((depth + 1) << kDepthShift) | (sameRunAsBefore && keptBefore ? kSameRun : 0u);
      waiting = m;
      keptBefore = true;
    } else {
      keptBefore = false;
    }
    sameRunAsBefore = (link & kSameRun) != 0;
    const uint32_t next = link & kNoPending;
    if (next == kNoPending) break;
    const WaitingSide side = view.waiting->giveBack(next);
    m = side.entry;
    link = side.link;
  }
  state.pending = waiting;
  state.pendingLink = waitingLink;
}

Sight DiscreteLineSweep::lookOlder(const PassView& view, const Vec3& centroid, const Vec3& normal,
                                   const LineState& state, Color& light) const {
  // With the tangent correction a grazed voxel is looked through: the two voxels before it
  // decide. The nearer is read from the record's slot where it lies, the other from its
  // reference: a slot put together here and read back at once stalls on its partial stores
  // (45% of this function's time when the first was copied out of the record).
  if (state.olderRef[0] == kNoVoxel) return Sight::Through;
  const Sight sight = look(
      view, centroid, [&] { return normal; }, state.older, view.unit, light,
      [&] { return centroidOf(view, state.olderRef[0]); });
  const uint32_t ref = state.olderRef[1];
  if (sight != Sight::Through || ref == kNoVoxel) return sight;
  if (ref & kCellRef) {
    uint32_t side = 0;
    const Sight cellSight = visibility_->look(centroid, normal, ref & ~kCellRef, view.unit, side);
    if (cellSight == Sight::Source) light = sideLight(view.source, side);
    return cellSight;
  }
  const Vec3 n = sideNormal(view.source, ref), refCentroid = centroidOf(view, ref);
  const Sight sideSight =
      planeSight(glm::dot(n, centroid - refCentroid), glm::dot(n, view.unit), view.tolerance);
  if (sideSight == Sight::Source) light = sideLight(view.source, ref);
  if (sideSight == Sight::Blocked && passesConvexEdge(normal, centroid, refCentroid, view.edge))
    return Sight::Through;
  return sideSight;
}

std::pair<uint32_t, uint32_t> DiscreteLineSweep::rowsInBand(uint32_t x,
                                                            const LineBand& band) const {
  return withinBand({grid_.slabRowBegin[x], grid_.slabRowBegin[x + 1]}, band, [&](uint32_t row) {
    return int64_t((lineTable_[0][x] + lineTable_[1][size_t(grid_.rowY[row])]) >> 32);
  });
}

std::pair<uint32_t, uint32_t> DiscreteLineSweep::zInBand(uint32_t x, const LineBand& band) const {
  return withinBand({0u, uint32_t(grid_.dims.z)}, band, [&](uint32_t z) {
    return int64_t((lineTable_[0][x] + lineTable_[2][z]) >> 32);
  });
}

template <typename F>
void DiscreteLineSweep::forEachCellInPassOrder(const IVec3& step, const LineBand& band,
                                               F&& f) const {
  // A line's row U depends on the dominant coordinate and the outer of the other two
  // (layoutLines): on x and y for a dominant x or y, so that a band is a range of each slab's
  // rows; on x and z for a dominant z, so that a band is a range of z, which cuts each row.
  const VoxelGrid& grid = grid_;
  const bool whole = band.holdsAll(rowStart_.size());
  const bool zDominant = layout_.axes[0] == 2;
  const bool cutRows = !whole && zDominant;
  const int16_t* const cellZ = grid.cellZ.data();
  const uint32_t* const slabs = occupiedSlabs_.data();
  forEach(0, uint32_t(occupiedSlabs_.size()), step.x >= 0, [&](uint32_t k) {
    const uint32_t x = slabs[k];
    const uint64_t slabLine = lineTable_[0][x];
    const int32_t slabDominant = dominantTable_[0][x];
    const auto rows = whole || cutRows ? std::pair(grid.slabRowBegin[x], grid.slabRowBegin[x + 1])
                                       : rowsInBand(x, band);
    const auto zs = cutRows ? zInBand(x, band) : std::pair(0u, uint32_t(grid.dims.z));
    if (zs.first == zs.second) return;  // near the z axis, a band's lines cross few slabs
    forEach(rows.first, rows.second, step.y >= 0, [&](uint32_t row) {
      auto [begin, end] = std::pair(grid.rowCellBegin[row], grid.rowCellBegin[row + 1]);
      if (cutRows) std::tie(begin, end) = cellsWithin(cellZ, begin, end, zs);
      if (begin == end) return;
      const size_t y = size_t(grid.rowY[row]);
      const uint64_t rowLine = slabLine + lineTable_[1][y];
      const int32_t rowDominant = slabDominant + dominantTable_[1][y];
      if (zDominant) {
        forEach(begin, end, step.z >= 0, [&](uint32_t cell) {
          const size_t z = size_t(cellZ[cell]);
          const uint64_t uv = rowLine + lineTable_[2][z];
          f(cell, uint32_t(rowStart_[uv >> 32] + int32_t(uint32_t(uv))),
            rowDominant + dominantTable_[2][z]);
        });
        return;
      }
      // Along a row of a dominant x or y only V moves (z's U and dominant parts are 0): the
      // row's lines start at one index.
      const int32_t rowFirst = rowStart_[rowLine >> 32] + int32_t(uint32_t(rowLine));
      const uint64_t* const inner = lineTable_[2].data();
      forEach(begin, end, step.z >= 0, [&](uint32_t cell) {
        f(cell, uint32_t(rowFirst + int32_t(uint32_t(inner[cellZ[cell]]))), rowDominant);
      });
    });
  });
}

template <bool kTangentCorrection>
void DiscreteLineSweep::pass(const IVec3& step, const LineBand& band, const Vec3& unit,
                             float weight, const Source& source, std::span<Color> gathered,
                             BandScratch& scratch) {
  const PassView view{grid_.cellEntryBegin.data(),
                      grid_.centroid.data(),
                      grid_.origin,
                      grid_.pointStep,
                      source,
                      gathered.data(),
                      &scratch.waiting,
                      &scratch.later,
                      unit,
                      weight,
                      visibility_->planeTolerance(),
                      visibility_->edgeTolerance()};
  LineState* const lines = scratch.recordsFor(grid_, band.lineCount, bandLines_);
  scratch.waiting.clear();  // the band's lines are new: none of their sides waits
  const uint16_t stamp = scratch.stamp;
  const uint32_t firstLine = band.firstLine;
  // Line records are scattered over the band's (up to a twenty-fourth of the scene's
  // cross-section), and the cells' own data is read in an order that jumps back row by row: fetch
  // both kAhead cells ahead of the visit so that the misses overlap instead of queueing.
  constexpr uint32_t kAhead = 32, kMask = kAhead - 1;
  uint32_t ringCell[kAhead], ringLine[kAhead];
  int32_t ringDominant[kAhead];
  uint32_t count = 0;
  auto visit = [&](uint32_t i) {
    const uint32_t cell = ringCell[i], begin = view.entryBegin[cell];
    LineState& state = lines[ringLine[i]];
    if (state.stamp != stamp) {
      state.stamp = stamp;
      state.recentRef = state.olderRef[0] = state.olderRef[1] = kNoVoxel;
      state.pending = state.pendingLink = kNoPending;
    }
    if (view.entryBegin[cell + 1] - begin == 1)
      visitSingleSide<kTangentCorrection>(view, begin, state, ringDominant[i]);
    else
      visitSeveralSides<kTangentCorrection>(view, cell, state, ringDominant[i]);
  };
  forEachCellInPassOrder(step, band, [&](uint32_t cell, uint32_t line, int32_t dominant) {
    line -= firstLine;  // the band's records hold its lines from firstLine on
    __builtin_prefetch(&lines[line], 1);
    const uint32_t first = view.entryBegin[cell];
    __builtin_prefetch(&view.centroid[first]);
    __builtin_prefetch(&view.gathered[first], 1);
    __builtin_prefetch(&view.source.normals[first]);
    __builtin_prefetch(&view.source.sides[first]);
    const uint32_t i = count++ & kMask;
    if (count > kAhead) visit(i);
    ringCell[i] = cell, ringLine[i] = line, ringDominant[i] = dominant;
  });
  for (uint32_t i = count > kAhead ? count - kAhead : 0; i < count; ++i) visit(i & kMask);
  scratch.later.addTo(view.gathered);
}

void DiscreteLineSweep::sweepPair(const DiscreteDirection& direction, const Source& source,
                                  std::span<Color> gathered, const LineOffset& offset) {
  prepareLines(direction.step, offset);
  const size_t threads = threadCount();
  cutBands(bandCountFor(threads, layout_.axes[0] == 2));
  const float weight = float(direction.solidAngle / 3.14159265358979323846) * source.scale;
  const Vec3 unit(direction.unit);
  auto sweepBand = [&](size_t b) {
    BandScratch& scratch = scratch_.local();
    if (settings_.tangentCorrection)
      pass<true>(direction.step, bands_[b], unit, weight, source, gathered, scratch);
    else
      pass<false>(direction.step, bands_[b], unit, weight, source, gathered, scratch);
  };
  if (threads == 1) {
    for (size_t b = 0; b < bands_.size(); ++b) sweepBand(b);
    return;
  }
  // Bands touch disjoint line records and sides (a side gathers from its own line only).
  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, bands_.size(), 1),
      [&](const tbb::blocked_range<size_t>& r) {
        for (size_t b = r.begin(); b != r.end(); ++b) sweepBand(b);
      },
      tbb::simple_partitioner());
}

std::vector<uint32_t> DiscreteLineSweep::lineOfEachCell(const IVec3& step,
                                                        const LineOffset& offset) {
  prepareLines(step, offset);
  std::vector<uint32_t> lines(grid_.cellCount());
  forEachCellInPassOrder(step, {},
                         [&](uint32_t cell, uint32_t line, int32_t) { lines[cell] = line; });
  return lines;
}

std::vector<uint32_t> DiscreteLineSweep::passOrder(const IVec3& step) {
  prepareLines(step);
  return cellsInPassOrder(step, {});
}

std::vector<uint32_t> DiscreteLineSweep::cellsInPassOrder(const IVec3& step,
                                                          const LineBand& band) const {
  std::vector<uint32_t> order;
  forEachCellInPassOrder(step, band,
                         [&](uint32_t cell, uint32_t, int32_t) { order.push_back(cell); });
  return order;
}

std::vector<std::vector<uint32_t>> DiscreteLineSweep::passOrderInBands(const IVec3& step,
                                                                       size_t bands) {
  prepareLines(step);
  cutBands(bands);
  std::vector<std::vector<uint32_t>> orders;
  for (const LineBand& band : bands_) orders.push_back(cellsInPassOrder(step, band));
  return orders;
}

}  // namespace rad
