// Properties of the discrete lines and of the voxelization they run through.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <map>
#include <random>
#include <set>

#include "core/rng.h"
#include "voxel/direction_set.h"
#include "voxel/discrete_line_sweep.h"
#include "voxel/voxel_test_scenes.h"
#include "voxel/voxelizer.h"

namespace rad {
namespace {

int64_t floorDiv(int64_t n, int64_t d) {
  return n >= 0 ? n / d : -((-n + d - 1) / d);
}

int dominantAxis(const IVec3& s) {
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(s[k]) > std::abs(s[axis])) axis = k;
  return axis;
}

// The naive line of cell p for direction s, straight from the definition (an independent form of
// the paper's floor((a y - b x + offset) / a)): for each non-dominant axis j, in the frame where
// the direction is positive, floor((a s_j p_j - |step_j| s_i p_i + offset_j) / a). The offsets go
// to the non-dominant axes by decreasing |component| (u first), as in the sweep.
std::array<int, 2> nonDominantAxes(const IVec3& s) {
  const int i = dominantAxis(s);
  std::array<int, 2> others{(i + 1) % 3, (i + 2) % 3};
  if (std::abs(s[others[1]]) > std::abs(s[others[0]]) ||
      (std::abs(s[others[1]]) == std::abs(s[others[0]]) && others[1] < others[0]))
    std::swap(others[0], others[1]);
  return others;
}

std::pair<int64_t, int64_t> naiveLine(const IVec3& p, const IVec3& s,
                                      const LineOffset& offset = {}) {
  const int i = dominantAxis(s);
  const std::array<int, 2> others = nonDominantAxes(s);
  const int64_t a = std::abs(s[i]), si = s[i] >= 0 ? 1 : -1;
  auto coord = [&](int axis, int64_t shift) {
    const int64_t sj = s[axis] >= 0 ? 1 : -1;
    return floorDiv(a * sj * p[axis] - std::abs(int64_t(s[axis])) * si * p[i] + shift, a);
  };
  return {coord(others[0], offset.u), coord(others[1], offset.v)};
}

std::vector<IVec3> randomSteps(int count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> component(-40, 40);
  std::vector<IVec3> steps;
  while (int(steps.size()) < count) {
    const IVec3 s(component(rng), component(rng), component(rng));
    if (s != IVec3(0)) steps.push_back(s);
  }
  // Axis-aligned, diagonal and tied directions, every sign.
  for (const IVec3& s : {IVec3(1, 0, 0), IVec3(0, -1, 0), IVec3(0, 0, 1), IVec3(1, 1, 0),
                         IVec3(-1, 1, 1), IVec3(2, -2, 1), IVec3(-3, 1, -3)})
    steps.push_back(s);
  return steps;
}

VoxelGrid sphereAndBoxGrid() {
  SceneBuilder b("shapes");
  const uint32_t m = b.addMaterial({"white", Color(0.5f), Color(0.0f), true});
  test::addSphere(b, Vec3(0.0f), 1.0f, false, m, b.addObject("sphere"));
  test::addInwardCube(b, [m](int) { return m; });
  VoxelizerSettings settings;
  settings.voxelSize = 0.05f;
  return voxelizeScene(b.build(), settings);
}

TEST(DiscreteLines, PartitionMatchesTheNaiveLineDefinition) {
  const VoxelGrid grid = sphereAndBoxGrid();
  ASSERT_GT(grid.cellCount(), 5000u);
  DiscreteLineSweep sweep(grid, {});
  std::vector<IVec3> cells(grid.cellCount());
  for (uint32_t c = 0; c < grid.cellCount(); ++c) cells[c] = grid.cellCoordinates(c);
  std::mt19937 rng(5);
  for (const IVec3& step : randomSteps(200, 7)) {
    SCOPED_TRACE(testing::Message() << "step " << step.x << " " << step.y << " " << step.z);
    // Half the directions with their lines shifted, as the solver's jitter does.
    const int64_t a = std::max({std::abs(step.x), std::abs(step.y), std::abs(step.z)});
    const LineOffset offset =
        rng() % 2 ? LineOffset{int64_t(rng() % a), int64_t(rng() % a)} : LineOffset{};
    const std::vector<uint32_t> lines = sweep.lineOfEachCell(step, offset);
    // Same partition both ways: equal table index <=> equal naive line.
    std::map<uint32_t, std::pair<int64_t, int64_t>> byIndex;
    std::map<std::pair<int64_t, int64_t>, uint32_t> byLine;
    for (uint32_t c = 0; c < grid.cellCount(); ++c) {
      const auto line = naiveLine(cells[c], step, offset);
      ASSERT_TRUE(byIndex.emplace(lines[c], line).first->second == line);
      ASSERT_EQ(byLine.emplace(line, lines[c]).first->second, lines[c]);
      ASSERT_LT(lines[c], sweep.lineCount());
    }
  }
}

// The solver sizes its memory before sweeping from this bound: each direction's table, with any
// line shift, must fit in it.
TEST(DiscreteLines, LineTableFitsTheBoundGivenBeforehand) {
  const VoxelGrid grid = sphereAndBoxGrid();
  std::mt19937 rng(3);
  for (const IVec3& step : randomSteps(100, 13)) {
    SCOPED_TRACE(testing::Message() << "step " << step.x << " " << step.y << " " << step.z);
    const int64_t a = std::max({std::abs(step.x), std::abs(step.y), std::abs(step.z)});
    DiscreteLineSweep sweep(grid, {});
    sweep.lineOfEachCell(step, LineOffset{int64_t(rng() % a), int64_t(rng() % a)});
    const size_t bound = maxLineCount(grid, std::span(&step, 1));
    EXPECT_LE(sweep.lineCount(), bound);
    EXPECT_GE(double(sweep.lineCount()), 0.8 * double(bound));  // and not far above it
  }
}

// The table holds a record for exactly the lines that cross the grid's box, counted here one
// voxel at a time. Seen along the diagonal (1, 1, 1) an X x Y x Z box is a hexagon of
// XY + YZ + ZX - X - Y - Z + 1 lines, where its bounding parallelogram has (X + Y - 1)(X + Z - 1).
TEST(DiscreteLines, LineTableHoldsOnlyTheLinesThroughTheBox) {
  const VoxelGrid grid = sphereAndBoxGrid();
  const IVec3 n = grid.dims;
  std::mt19937 rng(9);
  for (const IVec3& step : randomSteps(24, 17)) {
    SCOPED_TRACE(testing::Message() << "step " << step.x << " " << step.y << " " << step.z);
    const int64_t a = std::max({std::abs(step.x), std::abs(step.y), std::abs(step.z)});
    const LineOffset offset{int64_t(rng() % a), int64_t(rng() % a)};
    std::set<std::pair<int64_t, int64_t>> met;
    for (int x = 0; x < n.x; ++x)
      for (int y = 0; y < n.y; ++y)
        for (int z = 0; z < n.z; ++z) met.insert(naiveLine(IVec3(x, y, z), step, offset));
    DiscreteLineSweep sweep(grid, {});
    sweep.lineOfEachCell(step, offset);
    EXPECT_EQ(sweep.lineCount(), met.size());
  }
  DiscreteLineSweep diagonal(grid, {});
  diagonal.lineOfEachCell(IVec3(1, 1, 1));
  EXPECT_EQ(diagonal.lineCount(), size_t(n.x * n.y + n.y * n.z + n.z * n.x - n.x - n.y - n.z + 1));
}

TEST(DiscreteLines, SweepOrderAdvancesAlongTheDirection) {
  const VoxelGrid grid = sphereAndBoxGrid();
  DiscreteLineSweep sweep(grid, {});
  for (const IVec3& step : randomSteps(200, 11)) {
    SCOPED_TRACE(testing::Message() << "step " << step.x << " " << step.y << " " << step.z);
    const std::vector<uint32_t> lines = sweep.lineOfEachCell(step);
    for (const IVec3& passStep : {step, -step}) {
      std::map<uint32_t, IVec3> last;
      for (uint32_t c : sweep.passOrder(passStep)) {
        const IVec3 p = grid.cellCoordinates(c);
        auto it = last.find(lines[c]);
        if (it != last.end()) {
          const IVec3 d = p - it->second;
          // Every component moves with the direction's sign (or not at all), and the dominant
          // one moves: each line holds one voxel per dominant coordinate, met in order.
          for (int k = 0; k < 3; ++k) ASSERT_GE(d[k] * passStep[k], 0) << "axis " << k;
          ASSERT_GT(d[dominantAxis(step)] * passStep[dominantAxis(step)], 0);
        }
        last[lines[c]] = p;
      }
    }
  }
}

// Threads share a direction by bands of its lines: together the bands visit every cell once,
// all the cells of a line fall in one band, and a band meets its lines' cells in order along
// the direction (for a dominant z a band is a range of z in each slab, which cuts the rows).
// A band holds no more lines than its thread's records: cut 7 ways by cells, or not at all,
// bands holding more are cut further.
// Two spheres of radius 0.25 (outward), `apart` from each other along the diagonal of the xy
// plane, in voxels of 0.02: a box mostly empty, its slabs between the spheres without a cell.
VoxelGrid spheresApart(float apart) {
  SceneBuilder b("spheres apart");
  const uint32_t m = b.addMaterial({"white", Color(0.5f), Color(0.0f), false});
  test::addSphere(b, Vec3(0.0f), 0.25f, false, m, b.addObject("near"));
  test::addSphere(b, Vec3(apart, apart, 0.0f), 0.25f, false, m, b.addObject("far"));
  VoxelizerSettings settings;
  settings.voxelSize = 0.02f;
  return voxelizeScene(b.build(), settings);
}

// Every cell in exactly one band of each pass, each line in one band, its cells in order along
// the direction, and each band's lines within the records' limit (one band asked for: the limit
// must cut some passes).
void expectBandsSplitTheLinesInOrder(const VoxelGrid& grid) {
  DiscreteLineSweep sweep(grid, {});
  std::vector<IVec3> cells(grid.cellCount());
  for (uint32_t c = 0; c < grid.cellCount(); ++c) cells[c] = grid.cellCoordinates(c);
  size_t cutByLimit = 0;  // one-band passes the limit cuts: the case must come up
  for (const IVec3& step : randomSteps(200, 23)) {
    SCOPED_TRACE(testing::Message() << "step " << step.x << " " << step.y << " " << step.z);
    for (const IVec3& passStep : {step, -step}) {
      const std::vector<uint32_t> lines = sweep.lineOfEachCell(passStep);
      const size_t cuts = passStep == step ? 7 : 1;
      const std::vector<std::vector<uint32_t>> bands = sweep.passOrderInBands(passStep, cuts);
      ASSERT_GE(bands.size(), cuts);
      if (cuts == 1 && sweep.lineCount() > sweep.bandLineLimit()) {
        ASSERT_GT(bands.size(), 1u);
        ++cutByLimit;
      }
      std::vector<int> bandOfCell(grid.cellCount(), -1);
      std::map<uint32_t, int> bandOfLine;
      for (int b = 0; b < int(bands.size()); ++b) {
        std::map<uint32_t, IVec3> last;
        for (uint32_t c : bands[size_t(b)]) {
          ASSERT_EQ(bandOfCell[c], -1) << "cell " << c << " visited twice";
          bandOfCell[c] = b;
          ASSERT_EQ(bandOfLine.emplace(lines[c], b).first->second, b) << "line split";
          auto it = last.find(lines[c]);
          if (it != last.end()) {
            const IVec3 d = cells[c] - it->second;
            for (int k = 0; k < 3; ++k) ASSERT_GE(d[k] * passStep[k], 0) << "axis " << k;
            ASSERT_GT(d[dominantAxis(step)] * passStep[dominantAxis(step)], 0);
          }
          last[lines[c]] = cells[c];
        }
        // Lines are numbered row by row and a band is a range of rows: its lines are a range.
        if (last.empty()) continue;
        const size_t spanned = last.rbegin()->first - last.begin()->first + 1;
        EXPECT_LE(spanned, sweep.bandLineLimit()) << "band " << b;
      }
      EXPECT_EQ(std::count(bandOfCell.begin(), bandOfCell.end(), -1), 0);
    }
  }
  EXPECT_GT(cutByLimit, 0u);
}

TEST(DiscreteLines, BandsSplitTheLinesAndKeepEachLineInOrder) {
  expectBandsSplitTheLinesInOrder(sphereAndBoxGrid());
}

TEST(DiscreteLines, BandsOfAMostlyEmptyBoxSplitTheLinesAndKeepEachLineInOrder) {
  // The passes skip the slabs without cells, and the records' limit (a line per 8 sides) cuts
  // the lines into many more bands than a sixteenth.
  expectBandsSplitTheLinesInOrder(spheresApart(4.0f));
}

TEST(DiscreteLineSweep, MemoryGrowsWithTheSidesNotWithTheEmptyBox) {
  // Two spheres twice as far apart: the same sides, a box whose cross-section is about four
  // times as large. The line records were sized by the cross-section (a twenty-fourth of the
  // widest direction's lines a thread), so the sweep's memory grew with the square of the
  // distance: at 8 and 16, 690 kB and 2.13 MB for 5,872 sides (3.1x; checked with that sizing,
  // which fails both assertions). Now the records hold at most a line per 8 sides plus a row of
  // the table (as wide as the box): 193 and 244 kB (1.26x).
  tbb::task_arena oneThread(1);
  oneThread.execute([] {
    const DirectionSet directions(4);
    std::vector<IVec3> steps;
    for (size_t k = 0; k < directions.pairCount(); ++k)
      steps.push_back(directions.pairFirst(k).step);
    auto bytes = [&](const VoxelGrid& grid) {
      return double(DiscreteLineSweep::workingBytesFor(grid, maxLineCount(grid, steps)));
    };
    const VoxelGrid near = spheresApart(8.0f), far = spheresApart(16.0f);
    ASSERT_NEAR(double(far.entryCount()) / double(near.entryCount()), 1.0, 0.01);
    EXPECT_LT(bytes(far) / bytes(near), 2.0);
    // The far pair's, from the design: places for half the sides waiting at once and 1,024 more
    // (8 B each), 64-byte records for a row as wide as the box (x + y + z voxels) and a line per
    // 8 sides, the deferred light (4,096 items of 16 B) and the fold masks.
    const double sides = double(far.entryCount());
    const double row = double(far.dims.x + far.dims.y + far.dims.z);
    EXPECT_LE(bytes(far), (sides / 2.0 + 1024.0) * 8.0 + 64.0 * (sides / 8.0 + row) +
                              4096.0 * 16.0 + double(SideVisibility::maskBytesFor(far)));
  });
}

// Walks the naive line through `start` (a cell inside a closed surface) in direction s and
// reports whether it meets an occupied voxel before leaving the grid.
bool lineMeetsSurface(const VoxelGrid& grid, const IVec3& start, const IVec3& s) {
  const int i = dominantAxis(s);
  const auto line = naiveLine(start, s);
  const int step = s[i] > 0 ? 1 : -1;
  for (int xi = start[i] + step; xi >= 0 && xi < grid.dims[i]; xi += step) {
    // The unique cell of the line with dominant coordinate xi: solve the floor for each axis.
    IVec3 p = start;
    p[i] = xi;
    const std::array<int, 2> others = nonDominantAxes(s);
    for (int axis : others) {
      int lo = -2 * grid.dims[axis], hi = 2 * grid.dims[axis];
      const int64_t want = axis == others[0] ? line.first : line.second;
      // naiveLine is monotone in p[axis] (non-decreasing when signed): binary search.
      const int sj = s[axis] >= 0 ? 1 : -1;
      while (lo < hi) {
        const int mid = lo + (hi - lo) / 2;
        IVec3 q = p;
        q[axis] = mid * sj;
        const auto l = naiveLine(q, s);
        if ((axis == others[0] ? l.first : l.second) < want)
          lo = mid + 1;
        else
          hi = mid;
      }
      p[axis] = lo * sj;
    }
    if (grid.findCell(p) != UINT32_MAX) return true;
  }
  return false;
}

void expectTunnelFree(const Scene& scene, const Vec3& inside, float clearance, float voxelSize) {
  VoxelizerSettings settings;
  settings.voxelSize = voxelSize;
  const VoxelGrid grid = voxelizeScene(scene, settings);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> offset(-clearance, clearance);
  const DirectionSet directions(6);  // 354 directions, every octant
  int checked = 0;
  for (int trial = 0; trial < 8; ++trial) {
    const Vec3 p = inside + Vec3(offset(rng), offset(rng), offset(rng));
    const IVec3 start = IVec3(glm::floor((p - grid.origin) / grid.voxelSize));
    ASSERT_EQ(grid.findCell(start), UINT32_MAX);
    for (size_t d = 0; d < directions.size(); ++d, ++checked)
      ASSERT_TRUE(lineMeetsSurface(grid, start, directions[d].step))
          << "leak from " << start.x << "," << start.y << "," << start.z << " along "
          << directions[d].step.x << "," << directions[d].step.y << "," << directions[d].step.z;
  }
  EXPECT_GT(checked, 2000);
}

TEST(Voxelizer, ClosedBoxIsTunnelFree) {
  expectTunnelFree(test::uniformCube(Color(0.5f), Color(0.0f)), Vec3(0.5f), 0.3f, 0.037f);
}

TEST(Voxelizer, ClosedSphereIsTunnelFree) {
  SceneBuilder b("sphere");
  const uint32_t m = b.addMaterial({"white", Color(0.5f), Color(0.0f), false});
  test::addSphere(b, Vec3(0.1f, 0.2f, 0.3f), 1.0f, true, m, b.addObject("sphere"), 16, 32);
  expectTunnelFree(b.build(), Vec3(0.1f, 0.2f, 0.3f), 0.5f, 0.031f);
}

TEST(Voxelizer, AreasAddUpToTheSurface) {
  // The unit cube's six faces: area 6 (exact).
  VoxelizerSettings settings;
  settings.voxelSize = 0.043f;
  const VoxelGrid grid = voxelizeScene(test::uniformCube(Color(0.5f), Color(0.0f)), settings);
  double area = 0.0;
  for (size_t e = 0; e < grid.entryCount(); ++e) area += grid.areaOf(e);
  EXPECT_NEAR(area, 6.0, 1e-4);
  // Each face's voxels hold its normal.
  for (size_t e = 0; e < grid.entryCount(); ++e)
    EXPECT_NEAR(glm::length(grid.unitNormal(e)), 1.0f, 1e-4f);
}

// The count estimate sizes --voxels runs and refuses runs that memory will not hold: a cube and a
// sphere (curved: every normal) at several sizes stay within 10% of it (the cube's faces are
// exact up to the voxels along its edges, L^2 per face against 6 L^2).
TEST(Voxelizer, VoxelCountMatchesItsEstimate) {
  SceneBuilder b("sphere");
  const uint32_t m = b.addMaterial({"white", Color(0.5f), Color(0.0f), false});
  test::addSphere(b, Vec3(0.0f), 1.0f, true, m, b.addObject("sphere"), 32, 64);
  const Scene scenes[] = {test::uniformCube(Color(0.5f), Color(0.0f)), b.build()};
  for (const Scene& scene : scenes)
    for (const float size : {0.1f, 0.04f, 0.02f}) {
      VoxelizerSettings settings;
      settings.voxelSize = size;
      const double actual = double(voxelizeScene(scene, settings).cellCount());
      const double expected = expectedVoxelCount(scene, size);
      SCOPED_TRACE(testing::Message() << scene.name << " at " << size);
      EXPECT_NEAR(actual, expected, 0.10 * expected);
      // And the size for a count is its inverse.
      EXPECT_NEAR(voxelSizeForCount(scene, size_t(expected)), size, 1e-3f * size);
    }
}

TEST(Voxelizer, ThinTwoSidedWallKeepsOneEntryPerSide) {
  SceneBuilder b("wall");
  const uint32_t m = b.addMaterial({"white", Color(0.5f), Color(0.0f), true});
  test::addQuadFacing(b, test::axisSquare(Vec3(0.0f), 0, 1.0f), Vec3(1, 0, 0), m,
                      b.addObject("wall"));
  VoxelizerSettings settings;
  settings.voxelSize = 0.1f;
  const VoxelGrid grid = voxelizeScene(b.build(), settings);
  ASSERT_EQ(grid.entryCount(), 2 * grid.cellCount());
  for (uint32_t c = 0; c < grid.cellCount(); ++c) {
    const uint32_t e = grid.cellEntryBegin[c];
    EXPECT_NEAR(glm::dot(grid.unitNormal(e), grid.unitNormal(e + 1)), -1.0f, 1e-4f);
  }
}

// The voxelizer makes its pieces in parallel and sorts them in parallel by (cell, triangle,
// side), a key it takes to be unique: were it not, pieces with equal keys would be summed in an
// order that changes with the threads. A two-sided sphere in a box, on 1 and on 4 threads.
TEST(Voxelizer, SameGridWhateverTheThreadCount) {
  auto gridOn = [](int threads) {
    tbb::task_arena arena(threads);
    return arena.execute([] { return sphereAndBoxGrid(); });
  };
  const VoxelGrid one = gridOn(1), four = gridOn(4);
  EXPECT_EQ(one.cellZ, four.cellZ);
  EXPECT_EQ(one.cellEntryBegin, four.cellEntryBegin);
  EXPECT_EQ(one.orientation, four.orientation);
  EXPECT_EQ(one.centroid, four.centroid);
  EXPECT_EQ(one.faceArea, four.faceArea);
  EXPECT_EQ(one.surface, four.surface);
  EXPECT_EQ(one.surfaces, four.surfaces);
}

// A direction of the sweep with factor pi, so that w = 1 and a side gathers B cos.
DiscreteDirection unitWeightDirection(const IVec3& step) {
  return {step, glm::normalize(Vec3d(step)), glm::pi<double>()};
}

// Centroids are kept in 21-bit fixed point over the grid's box: any point of the box comes
// back within half a step (plus the float's rounding), and the step is the finest power-of-two
// fraction of a voxel whose 2^21 steps span the widest side (1/8,192 voxel at 256 voxels).
TEST(VoxelGrid, PackedPointsComeBackWithinHalfAStep) {
  for (const IVec3& dims : {IVec3(256, 40, 3), IVec3(300, 300, 300), IVec3(1, 1, 32767)}) {
    VoxelGrid grid;
    grid.origin = Vec3(-1000.0f, 2.5f, 0.125f);
    grid.voxelSize = 0.037f;
    grid.dims = dims;
    grid.pointStep = VoxelGrid::pointStepFor(dims, grid.voxelSize);
    const int widest = std::max({dims.x, dims.y, dims.z});
    EXPECT_LE(double(widest) * grid.voxelSize, double(grid.pointStep) * (1 << 21));
    EXPECT_GT(double(widest) * grid.voxelSize, double(grid.pointStep) * (1 << 20));
    if (widest == 256) {
      EXPECT_FLOAT_EQ(grid.pointStep * 8192.0f, grid.voxelSize);
    }
    Rng rng(7, uint64_t(widest));
    for (int i = 0; i < 1000; ++i) {
      Vec3d p;
      for (int k = 0; k < 3; ++k)
        p[k] = double(grid.origin[k]) + double(rng.uniform()) * dims[k] * grid.voxelSize;
      const Vec3 back = grid.unpack(grid.pack(p));
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(double(back[k]), p[k], 0.5 * grid.pointStep + 1e-6 * std::abs(p[k])) << i;
    }
  }
}

// Side surface indices take 2 bytes while they fit: the first index past 16 bits widens the
// array, and every index read back is the one stored, before and after.
TEST(VoxelGrid, SurfaceIndicesWidenPastSixteenBitsKeepingEveryIndex) {
  NarrowIndices indices;
  const std::vector<uint32_t> values = {0, 7, 65535, 65536, 3, 4000000000u};
  for (size_t i = 0; i < values.size(); ++i) {
    indices.push_back(values[i]);
    ASSERT_EQ(indices.size(), i + 1);
    for (size_t k = 0; k <= i; ++k) EXPECT_EQ(indices[k], values[k]) << i << " " << k;
    EXPECT_GE(indices.memoryBytes(), (i + 1) * (i >= 3 ? 4 : 2));  // widened at 65536
  }
  NarrowIndices narrow;
  for (uint32_t v : {0u, 7u, 65535u}) narrow.push_back(v);
  EXPECT_LT(narrow.memoryBytes(), 3 * sizeof(uint32_t));
}

// Two parallel plates 0.6 apart facing each other, voxelized at 0.1: objects "a" (x = 0, facing
// +x) and "b" (x = 0.6, facing -x).
VoxelGrid facingPlates() {
  SceneBuilder b("plates");
  const uint32_t m = b.addMaterial({"white", Color(0.5f), Color(0.0f), false});
  test::addQuadFacing(b, test::axisSquare(Vec3(0.0f), 0, 1.0f), Vec3(1, 0, 0), m, b.addObject("a"));
  test::addQuadFacing(b, test::axisSquare(Vec3(0.6f, 0.0f, 0.0f), 0, 1.0f), Vec3(-1, 0, 0), m,
                      b.addObject("b"));
  VoxelizerSettings settings;
  settings.voxelSize = 0.1f;
  return voxelizeScene(b.build(), settings);
}

TEST(DiscreteLineSweep, FacingPlatesGetTheSameLightWhicheverWayTheLinesRun) {
  // In one traversal along s the plate behind waits for light from ahead while the other looks
  // back: both ways must give every side B cos w = 1 along the normal.
  const VoxelGrid grid = facingPlates();
  std::vector<DiscreteLineSweep::SentLight> slots(grid.entryCount());
  const DiscreteLineSweep::Source source = DiscreteLineSweep::packSides(
      grid, [](size_t) { return Color(1.0f); }, slots);
  for (const IVec3& step : {IVec3(1, 0, 0), IVec3(-1, 0, 0)}) {
    DiscreteLineSweep sweep(grid, {});
    std::vector<Color> gathered(grid.entryCount(), Color(0.0f));
    sweep.sweepPair(unitWeightDirection(step), source, gathered);
    for (size_t e = 0; e < grid.entryCount(); ++e) EXPECT_FLOAT_EQ(gathered[e].x, 1.0f) << e;
  }
  // At 45 degrees, the lines from one plate's lower rows reach the other's upper rows (6 voxels
  // up): each side that sees the other plate gets cos 45 degrees, and the two plates get the same
  // total (each line is one exchange).
  for (const IVec3& step : {IVec3(1, 1, 0), IVec3(-1, -1, 0)}) {
    DiscreteLineSweep sweep(grid, {});
    std::vector<Color> gathered(grid.entryCount(), Color(0.0f));
    sweep.sweepPair(unitWeightDirection(step), source, gathered);
    double total[2] = {0.0, 0.0};
    for (size_t e = 0; e < grid.entryCount(); ++e) {
      const float g = gathered[e].x;
      EXPECT_TRUE(g == 0.0f || std::abs(g - std::sqrt(0.5f)) < 1e-6f) << e << " " << g;
      total[grid.objectOf(e)] += g;
    }
    EXPECT_GT(total[0], 0.0);
    EXPECT_DOUBLE_EQ(total[0], total[1]);
  }
}

TEST(DiscreteLineSweep, EveryVoxelOfAGrazingRunGetsTheLightAhead) {
  // A floor and, beyond its end, a wall. Lines of (4, 1, 0) run along the floor for about four
  // voxels before they rise to the wall, so the floor's sides (facing ahead, they wait on their
  // lines) wait in runs: every one of them, not only a run's nearest, must get the wall's light.
  SceneBuilder b("floor and wall");
  const uint32_t m = b.addMaterial({"white", Color(0.5f), Color(0.0f), false});
  const uint32_t floorObject = b.addObject("floor");
  test::addQuadFacing(b, test::axisSquare(Vec3(0.5f, 0.0f, 0.5f), 1, 1.0f), Vec3(0, 1, 0), m,
                      floorObject);
  test::addQuadFacing(b, test::axisSquare(Vec3(1.25f, 0.5f, 0.5f), 0, 1.0f), Vec3(-1, 0, 0), m,
                      b.addObject("wall"));
  VoxelizerSettings settings;
  settings.voxelSize = 0.1f;
  const VoxelGrid grid = voxelizeScene(b.build(), settings);
  std::vector<DiscreteLineSweep::SentLight> slots(grid.entryCount());
  const DiscreteLineSweep::Source source = DiscreteLineSweep::packSides(
      grid, [&](size_t e) { return Color(grid.objectOf(e) == floorObject ? 0.0f : 1.0f); }, slots);
  DiscreteLineSweep sweep(grid, {});
  std::vector<Color> gathered(grid.entryCount(), Color(0.0f));
  sweep.sweepPair(unitWeightDirection(IVec3(4, 1, 0)), source, gathered);
  size_t floorSides = 0;
  for (size_t e = 0; e < grid.entryCount(); ++e) {
    if (grid.objectOf(e) != floorObject) continue;
    ++floorSides;
    EXPECT_NEAR(gathered[e].x, 1.0f / std::sqrt(17.0f), 1e-4f) << e;  // cos = n . s = 1 / sqrt(17)
  }
  EXPECT_GT(floorSides, 100u);
}

}  // namespace
}  // namespace rad
