#include "voxel/discrete_line_sweep.h"

#include <algorithm>
#include <cstdlib>
#include <limits>

namespace rad {

namespace {

constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

// Points closer than this (in voxels) to a plane lie in it: a grazing line runs inside it.
constexpr float kPlaneTolerance = 0.05f;
// Normals within about 8 degrees belong to one plane.
constexpr float kSamePlaneCos = 0.99f;

int64_t floorDiv(int64_t n, int64_t d) { return n >= 0 ? n / d : -((-n + d - 1) / d); }
int64_t ceilDiv(int64_t n, int64_t d) { return -floorDiv(-n, d); }

// Calls f(i) for i in [begin, end), ascending or descending.
template <typename F>
inline void forEach(uint32_t begin, uint32_t end, bool ascending, F&& f) {
  if (ascending) {
    for (uint32_t i = begin; i < end; ++i) f(i);
  } else {
    for (uint32_t i = end; i-- > begin;) f(i);
  }
}

}  // namespace

DiscreteLineSweep::DiscreteLineSweep(const VoxelGrid& grid, const SweepSettings& settings)
    : grid_(grid), settings_(settings) {}

void DiscreteLineSweep::prepareLines(const IVec3& step) {
  // Axes by decreasing |component|: d[0] dominant. Components a >= b >= c >= 0 after signing.
  std::array<int, 3> d{0, 1, 2};
  std::stable_sort(d.begin(), d.end(), [&](int i, int j) { return std::abs(step[i]) > std::abs(step[j]); });
  const int64_t a = std::abs(step[d[0]]), b = std::abs(step[d[1]]), c = std::abs(step[d[2]]);
  std::array<std::vector<int64_t>, 3> u, v;
  int64_t uSpan = 0, vSpan = 0;
  std::array<int64_t, 3> uMin{}, vMin{};
  for (int k = 0; k < 3; ++k) {
    const int64_t sign = step[d[k]] >= 0 ? 1 : -1;
    const int n = grid_.dims[d[k]];
    u[k].resize(size_t(n));
    v[k].resize(size_t(n));
    for (int t = 0; t < n; ++t) {
      const int64_t m = sign * t;  // coordinate in the frame where the direction is positive
      u[k][size_t(t)] = k == 0 ? -ceilDiv(b * m, a) : (k == 1 ? m : 0);
      v[k][size_t(t)] = k == 0 ? -ceilDiv(c * m, a) : (k == 2 ? m : 0);
    }
    const auto [ulo, uhi] = std::minmax_element(u[k].begin(), u[k].end());
    const auto [vlo, vhi] = std::minmax_element(v[k].begin(), v[k].end());
    uMin[size_t(k)] = *ulo;
    vMin[size_t(k)] = *vlo;
    uSpan += *uhi - *ulo;
    vSpan += *vhi - *vlo;
  }
  const int64_t nv = vSpan + 1;
  for (int k = 0; k < 3; ++k) {
    const int axis = d[k];
    const int64_t sign = step[axis] >= 0 ? 1 : -1;
    lineTable_[axis].resize(u[k].size());
    dominantTable_[axis].assign(u[k].size(), 0);
    for (size_t t = 0; t < u[k].size(); ++t) {
      lineTable_[axis][t] = int32_t((u[k][t] - uMin[size_t(k)]) * nv + (v[k][t] - vMin[size_t(k)]));
      if (k == 0) dominantTable_[axis][t] = int32_t(sign * int64_t(t));
    }
  }
  const size_t lineCount = size_t((uSpan + 1) * nv);
  if (lines_.size() < lineCount) lines_.resize(lineCount);
}

DiscreteLineSweep::Sight DiscreteLineSweep::look(uint32_t e, uint32_t q, const Vec3& unit,
                                                 uint32_t& source) const {
  // The backward ray ce - t unit, t > 0, meets the plane of side f at t = height / approach
  // when the signs agree; a ray in the plane or leaving it grazes f. The nearest plane met
  // within its polygon (as far as the cell's folds tell) decides: its front is the source,
  // its back blocks.
  const float tolerance = kPlaneTolerance * grid_.voxelSize;
  const Vec3 ce = grid_.centroid[e];
  Sight sight = Sight::Through;
  float nearest = std::numeric_limits<float>::max();
  for (uint32_t f = grid_.cellEntryBegin[q]; f < grid_.cellEntryBegin[q + 1]; ++f) {
    const Vec3 nf = grid_.normal[f];
    const float height = glm::dot(nf, ce - grid_.centroid[f]);
    const float approach = glm::dot(nf, unit);
    if (std::abs(height) <= tolerance || height * approach <= 0.0f) continue;
    const float t = height / approach;
    if (t >= nearest || !insideFold(f, q, ce - t * unit, ce)) continue;
    nearest = t;
    sight = height > 0.0f ? Sight::Source : Sight::Blocked;
    source = f;
  }
  return sight;
}

bool DiscreteLineSweep::insideFold(uint32_t f, uint32_t q, const Vec3& point,
                                   const Vec3& origin) const {
  // Where f meets another side g of the cell in a concave fold (g stands in front of f), f's
  // polygon ends at g's plane: a crossing of f's plane behind g is past the edge of f.
  // The fold's own edge is sharp: a side lying in g's plane is not in front of it.
  const float tolerance = kPlaneTolerance * grid_.voxelSize, edge = 1e-3f * grid_.voxelSize;
  for (uint32_t g = grid_.cellEntryBegin[q]; g < grid_.cellEntryBegin[q + 1]; ++g) {
    if (g == f || glm::dot(grid_.normal[f], grid_.centroid[g] - grid_.centroid[f]) <= tolerance) continue;
    // The crossing must lie in front of g, and so must the ray's origin: a ray from behind g
    // reaches f's front only through g.
    if (glm::dot(grid_.normal[g], point - grid_.centroid[g]) < -edge ||
        glm::dot(grid_.normal[g], origin - grid_.centroid[g]) < -edge)
      return false;
  }
  return true;
}

bool DiscreteLineSweep::lookWithinCell(uint32_t e, uint32_t cell, const Vec3& unit,
                                       uint32_t& source) const {
  // Planes, not polygons, are known here, so only sides of a concave fold (each in front of
  // the other: a room's inner edge or corner) may see each other; the outer sides of a convex
  // corner, or a wall's two sides, never do.
  const float tolerance = kPlaneTolerance * grid_.voxelSize;
  float best = 0.0f;
  for (uint32_t f = grid_.cellEntryBegin[cell]; f < grid_.cellEntryBegin[cell + 1]; ++f) {
    const Vec3 gap = grid_.centroid[e] - grid_.centroid[f];
    const float approach = glm::dot(grid_.normal[f], unit);
    if (f == e || glm::dot(grid_.normal[f], gap) <= tolerance ||
        -glm::dot(grid_.normal[e], gap) <= tolerance || approach <= best)
      continue;
    best = approach;
    source = f;
  }
  return best > 0.0f;
}

bool DiscreteLineSweep::continuesPlanes(uint32_t p, uint32_t q) const {
  const uint32_t pBegin = grid_.cellEntryBegin[p], pEnd = grid_.cellEntryBegin[p + 1];
  const uint32_t qBegin = grid_.cellEntryBegin[q], qEnd = grid_.cellEntryBegin[q + 1];
  if (pEnd - pBegin != qEnd - qBegin) return false;
  const float tolerance = kPlaneTolerance * grid_.voxelSize;
  for (uint32_t a = pBegin; a < pEnd; ++a) {
    bool matched = false;
    for (uint32_t b = qBegin; b < qEnd && !matched; ++b)
      matched = glm::dot(grid_.normal[a], grid_.normal[b]) > kSamePlaneCos &&
                std::abs(glm::dot(grid_.normal[b], grid_.centroid[a] - grid_.centroid[b])) <= tolerance;
    if (!matched) return false;
  }
  return true;
}

void DiscreteLineSweep::remember(LineState& state, uint32_t cell, int32_t dominant) const {
  const bool adjacent = state.count > 0 && std::abs(dominant - state.lastDominant) == 1;
  if (settings_.tangentCorrection && adjacent && continuesPlanes(cell, state.cells[0])) {
    state.cells[0] = cell;  // a run along the same planes stays one slot
  } else {
    for (int i = kHistory - 1; i > 0; --i) state.cells[i] = state.cells[i - 1];
    state.cells[0] = cell;
    state.count = std::min<uint32_t>(state.count + 1, kHistory);
  }
  state.lastDominant = dominant;
}

void DiscreteLineSweep::visitCell(uint32_t cell, uint32_t line, int32_t dominant, const Vec3& unit,
                                  float weight, std::span<const Color> radiosity,
                                  std::span<glm::vec4> gathered) {
  LineState& state = lines_[line];
  if (state.stamp != stamp_) state.stamp = stamp_, state.count = 0;
  const uint32_t end = grid_.cellEntryBegin[cell + 1];
  for (uint32_t e = grid_.cellEntryBegin[cell]; e < end; ++e) {
    const float cosine = -glm::dot(grid_.normal[e], unit);
    if (cosine <= 0.0f) continue;
    gathered[e].w += cosine * weight;
    // The cell's own other sides first (the faces of an edge or a corner see each other), then
    // the voxels behind it. Without tangent correction the first voxel behind hides the rest.
    const uint32_t depth = settings_.tangentCorrection ? state.count : std::min<uint32_t>(state.count, 1);
    uint32_t source = kNone;
    if (end - grid_.cellEntryBegin[cell] > 1 && lookWithinCell(e, cell, unit, source)) {
      gathered[e] += glm::vec4(radiosity[source] * (cosine * weight), 0.0f);
      continue;
    }
    for (uint32_t i = 0; i < depth; ++i) {
      const Sight sight = look(e, state.cells[i], unit, source);
      if (sight == Sight::Through && settings_.tangentCorrection) continue;
      if (sight == Sight::Source) gathered[e] += glm::vec4(radiosity[source] * (cosine * weight), 0.0f);
      break;
    }
  }
  remember(state, cell, dominant);
}

void DiscreteLineSweep::pass(const IVec3& step, const Vec3& unit, float weight,
                             std::span<const Color> radiosity, std::span<glm::vec4> gathered) {
  ++stamp_;
  const bool ascX = step.x >= 0, ascY = step.y >= 0, ascZ = step.z >= 0;
  const VoxelGrid& g = grid_;
  forEach(0, uint32_t(g.dims.x), ascX, [&](uint32_t x) {
    const int32_t slabLine = lineTable_[0][x], slabDominant = dominantTable_[0][x];
    forEach(g.slabRowBegin[x], g.slabRowBegin[x + 1], ascY, [&](uint32_t row) {
      const int32_t y = g.rowY[row];
      const int32_t rowLine = slabLine + lineTable_[1][size_t(y)];
      const int32_t rowDominant = slabDominant + dominantTable_[1][size_t(y)];
      forEach(g.rowCellBegin[row], g.rowCellBegin[row + 1], ascZ, [&](uint32_t cell) {
        const size_t z = size_t(g.cellZ[cell]);
        visitCell(cell, uint32_t(rowLine + lineTable_[2][z]), rowDominant + dominantTable_[2][z],
                  unit, weight, radiosity, gathered);
      });
    });
  });
}

void DiscreteLineSweep::sweepPair(const DiscreteDirection& direction, std::span<const Color> radiosity,
                                  std::span<glm::vec4> gathered) {
  prepareLines(direction.step);
  const float weight = float(direction.solidAngle / 3.14159265358979323846);
  const Vec3 unit(direction.unit);
  pass(direction.step, unit, weight, radiosity, gathered);
  pass(-direction.step, -unit, weight, radiosity, gathered);
}

std::vector<uint32_t> DiscreteLineSweep::lineOfEachCell(const IVec3& step) {
  prepareLines(step);
  std::vector<uint32_t> lines(grid_.cellCount());
  for (uint32_t x = 0; x < uint32_t(grid_.dims.x); ++x)
    for (uint32_t row = grid_.slabRowBegin[x]; row < grid_.slabRowBegin[x + 1]; ++row)
      for (uint32_t cell = grid_.rowCellBegin[row]; cell < grid_.rowCellBegin[row + 1]; ++cell)
        lines[cell] = uint32_t(lineTable_[0][x] + lineTable_[1][size_t(grid_.rowY[row])] +
                               lineTable_[2][size_t(grid_.cellZ[cell])]);
  return lines;
}

std::vector<uint32_t> DiscreteLineSweep::passOrder(const IVec3& step) const {
  std::vector<uint32_t> order;
  forEach(0, uint32_t(grid_.dims.x), step.x >= 0, [&](uint32_t x) {
    forEach(grid_.slabRowBegin[x], grid_.slabRowBegin[x + 1], step.y >= 0, [&](uint32_t row) {
      forEach(grid_.rowCellBegin[row], grid_.rowCellBegin[row + 1], step.z >= 0,
              [&](uint32_t cell) { order.push_back(cell); });
    });
  });
  return order;
}

}  // namespace rad
