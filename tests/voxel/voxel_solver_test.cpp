// Physics of the voxel solver: furnace, energy balance, no light leaks.
#include "voxel/voxel_solver.h"

#include <gtest/gtest.h>
#include <radiosity/error.h>
#include <radiosity/voxel_radiosity.h>
#include <tbb/task_arena.h>

#include <array>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtx/component_wise.hpp>

#include "core/address_space_limit.h"
#include "voxel/voxel_test_scenes.h"
#include "voxel/voxelizer.h"

namespace rad {
namespace {

VoxelGrid voxelize(const Scene& scene, float voxelSize) {
  VoxelizerSettings settings;
  settings.voxelSize = voxelSize;
  return voxelizeScene(scene, settings);
}

// A cube of side `size` centred at `centre`, turned by `turn`, its faces facing in or out.
void addTurnedCube(SceneBuilder& b, const Vec3& centre, float size, const glm::mat3& turn,
                   bool inward, uint32_t material, uint32_t object) {
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      Vec3 offset(0.0f);
      offset[axis] = side == 0 ? -0.5f * size : 0.5f * size;
      std::array<Vec3, 4> quad = test::axisSquare(offset, axis, size);
      for (Vec3& p : quad) p = centre + turn * p;
      test::addQuadFacing(b, quad, turn * (inward ? -offset : offset), material, object);
    }
}

// Turned about two axes, so that no face lies along the grid.
glm::mat3 oddTurn() {
  return glm::mat3(glm::rotate(glm::mat4(1.0f), 0.5f, Vec3(0, 1, 0))) *
         glm::mat3(glm::rotate(glm::mat4(1.0f), 0.35f, Vec3(1, 0, 0)));
}

// A furnace's solve of `iterations` iterations: every surface emits, so no first shot; R = 8,
// and `later` for the sweeps after the first (0: the same).
VoxelSolution solveFurnace(const Scene& scene, const VoxelGrid& grid, int iterations,
                           int later = 0) {
  VoxelSolverSettings settings;
  settings.sphereRadius = 8;
  settings.laterSphereRadius = later;
  settings.iterations = iterations;
  settings.tolerance = 0.0;  // that many
  settings.directFirstShot = false;
  return solveVoxelRadiosity(scene, grid, settings);
}

TEST(VoxelSolver, UniformFurnaceConvergesToEOverOneMinusRho) {
  // Closed enclosure, every surface emits E and reflects rho: B = E / (1 - rho) everywhere
  // (docs/references.md 3.2). With per-voxel normalization every side gathers a full hemisphere.
  const Color ke(1.0f, 0.5f, 0.25f);
  const Scene scene = test::uniformCube(Color(0.5f), ke);
  const VoxelGrid grid = voxelize(scene, 1.0f / 24.0f);
  const VoxelSolution s = solveFurnace(scene, grid, 24);
  const Color expected = glm::pi<float>() * ke / 0.5f;
  for (size_t e = 0; e < grid.entryCount(); ++e)
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(s.radiosity[e][c], expected[c], 1e-3f * expected[c]) << e;
  // Each bounce carries half the one before: the 24th adds 0.5^24 of the light put in.
  EXPECT_LT(s.residuals.back(), 1e-6);
}

TEST(VoxelSolver, FurnaceHoldsWithACoarserSphereForLaterBounces) {
  // The sweeps after the first on a sphere of R = 3 (90 directions, against 606 at R = 8; python3
  // brute-force counts of the digital sphere): each bounce is normalized for the sphere it was
  // gathered on, so every side still gathers a whole hemisphere and B = E / (1 - rho)
  // (docs/references.md 3.2). Normalized for R = 8, the bounces gathered on R = 3 came out off.
  const Color ke(1.0f, 0.5f, 0.25f);
  const Scene scene = test::uniformCube(Color(0.5f), ke);
  const VoxelGrid grid = voxelize(scene, 1.0f / 24.0f);
  const VoxelSolution s = solveFurnace(scene, grid, 24, 3);
  EXPECT_EQ(s.directions, 606u);
  EXPECT_EQ(s.laterDirections, 90u);
  const Color expected = glm::pi<float>() * ke / 0.5f;
  for (size_t e = 0; e < grid.entryCount(); ++e)
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(s.radiosity[e][c], expected[c], 1e-3f * expected[c]) << e;
}

// B over the objects `addObject` adds to the furnace (every surface emits E = pi and reflects
// rho = 0.5 inside the unit cube), area-weighted: pi / (1 - rho) if every ray from them meets a
// surface (docs/references.md 3.2).
template <typename AddObject>
double meanRadiosityInFurnace(const AddObject& addObject, float voxelSize) {
  SceneBuilder b("furnace with an object");
  const uint32_t m = b.addMaterial({"white", Color(0.5f), Color(1.0f), false});
  test::addInwardCube(b, [m](int) { return m; });
  const uint32_t object = b.addObject("object");
  addObject(b, m, object);
  const Scene scene = b.build();
  const VoxelGrid grid = voxelize(scene, voxelSize);
  const VoxelSolution s = solveFurnace(scene, grid, 16);
  double area = 0.0, power = 0.0;
  for (size_t e = 0; e < grid.entryCount(); ++e)
    if (grid.objectOf(e) == object)
      area += grid.areaOf(e), power += grid.areaOf(e) * s.radiosity[e].x;
  return power / area;
}

TEST(VoxelSolver, FurnaceHoldsAroundATurnedBox) {
  // A box turned at odd angles floating in the furnace. Rays that pass the box's convex edges
  // outside must not take the plane of the face around the corner for a wall (its back): before
  // they did, and the box's B came out 5.2% low.
  const double b = meanRadiosityInFurnace(
      [](SceneBuilder& builder, uint32_t m, uint32_t box) {
        addTurnedCube(builder, Vec3(0.45f, 0.5f, 0.55f), 0.4f, oddTurn(), false, m, box);
      },
      1.0f / 24.0f);
  const double expected = glm::pi<double>() / 0.5;
  EXPECT_NEAR(b, expected, 0.015 * expected);
}

TEST(VoxelSolver, FurnaceHoldsAroundASphere) {
  // A ball in the furnace. A curved surface is convex from voxel to voxel: a ray leaving a side
  // near its tangent crosses the plane of the next side of the ball from behind, past that
  // side's polygon (in the open). Taken for the back of a surface, 12% of the rays found
  // nothing, and the ball's B came out 10.9% low.
  const double b = meanRadiosityInFurnace(
      [](SceneBuilder& builder, uint32_t m, uint32_t ball) {
        test::addSphere(builder, Vec3(0.5f, 0.45f, 0.55f), 0.2f, false, m, ball);
      },
      1.0f / 48.0f);
  const double expected = glm::pi<double>() / 0.5;
  EXPECT_NEAR(b, expected, 0.015 * expected);
}

double weightedSum(const VoxelGrid& grid, const std::vector<Color>& values, int channel) {
  double sum = 0.0;
  for (size_t e = 0; e < grid.entryCount(); ++e) sum += grid.areaOf(e) * values[e][channel];
  return sum;
}

// The inward cube, walls of rho 0.6 and its face 3 a lamp (rho 0.5, Ke = lampKe); returns the
// wall material, for what a test adds to the room.
uint32_t addLampRoom(SceneBuilder& b, float lampKe) {
  const uint32_t wall = b.addMaterial({"wall", Color(0.6f), Color(0.0f), false});
  const uint32_t lamp = b.addMaterial({"lamp", Color(0.5f), Color(lampKe), false});
  test::addInwardCube(b, [&](int face) { return face == 3 ? lamp : wall; });
  return wall;
}

// The lamp room in voxels of 1/n, with the coarse settings the quick tests solve it with
// (R = 6, 4 shadow rays a side).
struct CoarseLampRoom {
  Scene scene;
  VoxelGrid grid;
  VoxelSolverSettings settings;
};
CoarseLampRoom coarseLampRoom(float lampKe, float n) {
  SceneBuilder b("room");
  addLampRoom(b, lampKe);
  CoarseLampRoom room{b.build(), {}, {}};
  room.grid = voxelize(room.scene, 1.0f / n);
  room.settings.sphereRadius = 6;
  room.settings.directSamples = 4;
  return room;
}

// The inward cube, every face of one rho and face 3 a lamp (Ke = 1), in voxels of 1/20, with
// what a closed enclosure's energy balance asks of it: sum A B = sum A E / (1 - rho) exactly
// (docs/references.md 3.1), per channel.
struct UniformRoom {
  Scene scene;
  VoxelGrid grid;
  VoxelSolverSettings settings;
  std::array<double, 3> balancedPower{};  ///< sum A B per channel at equilibrium
};
UniformRoom uniformRoom(const Color& rho) {
  SceneBuilder b("room");
  const uint32_t wall = b.addMaterial({"wall", rho, Color(0.0f), false});
  const uint32_t lamp = b.addMaterial({"lamp", rho, Color(1.0f), false});
  test::addInwardCube(b, [&](int face) { return face == 3 ? lamp : wall; });
  UniformRoom room{b.build(), {}, {}, {}};
  room.grid = voxelize(room.scene, 1.0f / 20.0f);
  room.settings.sphereRadius = 10;
  room.settings.directSamples = 16;
  std::vector<Color> emitted(room.grid.entryCount());
  for (size_t e = 0; e < emitted.size(); ++e)
    emitted[e] = glm::pi<float>() * room.grid.materialOf(e).emission;
  for (int c = 0; c < 3; ++c)
    room.balancedPower[size_t(c)] = weightedSum(room.grid, emitted, c) / (1.0 - double(rho[c]));
  return room;
}

TEST(VoxelSolver, ClosedRoomBalancesEnergy) {
  // Uniform rho = 0.5, emitter included: the voxel method must hold the balance to 2%.
  UniformRoom room = uniformRoom(Color(0.5f));
  room.settings.iterations = 30;
  for (bool firstShot : {false, true}) {
    SCOPED_TRACE(firstShot ? "first shot" : "pure sweep");
    room.settings.directFirstShot = firstShot;
    const VoxelSolution s = solveVoxelRadiosity(room.scene, room.grid, room.settings);
    const double expected = room.balancedPower[0];
    EXPECT_NEAR(weightedSum(room.grid, s.radiosity, 0), expected, 0.02 * expected);
  }
}

TEST(VoxelSolver, BrightRoomBalancesEnergyAfterFiveIterations) {
  // Walls of rho 0.8 send on 80% of each bounce, so five iterations after the first shot leave out
  // 0.8^6 = 26% of the reflected light: sum A B = sum A E (1 + rho (1 - 0.8^6) / (1 - rho)), 21%
  // below sum A E / (1 - rho) (docs/references.md 3.1). The tail estimate adds the bounces after
  // the last, extrapolated from the last two: the balance must hold to 2% with it.
  UniformRoom room = uniformRoom(Color(0.8f));
  room.settings.iterations = 5;
  const double expected = room.balancedPower[0];
  const VoxelSolution s = solveVoxelRadiosity(room.scene, room.grid, room.settings);
  EXPECT_NEAR(weightedSum(room.grid, s.radiosity, 0), expected, 0.02 * expected);
  EXPECT_GT(s.tailShare, 0.15);  // the missing 21%, extrapolated
  room.settings.estimateTail = false;
  const VoxelSolution truncated = solveVoxelRadiosity(room.scene, room.grid, room.settings);
  EXPECT_NEAR(weightedSum(room.grid, truncated.radiosity, 0), 0.79 * expected, 0.02 * expected);
}

TEST(VoxelSolver, ColouredRoomBalancesEnergyInEveryChannelAfterFiveIterations) {
  // Walls sending on 80% of red, 50% of green and 20% of blue: each channel's bounces fall by
  // their own ratio, and the tail must follow each (2% asked per channel). One ratio of the
  // luminance's powers after five iterations, sum_c w_c rho_c^5 / sum_c w_c rho_c^4 with the
  // luminance weights w = (0.2126, 0.7152, 0.0722), is 0.70 where red's is 0.8: it adds 2.3
  // last bounces to red instead of 4 (checked: red 7.7% dark).
  UniformRoom room = uniformRoom(Color(0.8f, 0.5f, 0.2f));
  room.settings.iterations = 5;
  const VoxelSolution s = solveVoxelRadiosity(room.scene, room.grid, room.settings);
  for (int c = 0; c < 3; ++c) {
    SCOPED_TRACE(testing::Message() << "channel " << c);
    const double expected = room.balancedPower[size_t(c)];
    EXPECT_NEAR(weightedSum(room.grid, s.radiosity, c), expected, 0.02 * expected);
  }
}

TEST(VoxelSolver, ResidualFallsPastTheNoiseOfTheJitteredLines) {
  // The lines shift every iteration, so B's value at a side changes from one iteration to the
  // next by more than the light added (the discretization's noise, about 1e-3 of B here).
  // The residual is the power of the bounce each iteration adds, all positive, which falls by
  // the walls' albedo every iteration: a tolerance of 1e-6 must stop the solve early.
  CoarseLampRoom room = coarseLampRoom(1.0f, 16.0f);
  room.settings.iterations = 60;
  room.settings.tolerance = 1e-6;
  const VoxelSolution s = solveVoxelRadiosity(room.scene, room.grid, room.settings);
  ASSERT_LT(s.residuals.size(), 40u);
  EXPECT_LT(s.residuals.back(), 1e-6);
  // The residuals fall geometrically, by the albedo light meets: in a closed cube that gathers
  // whole hemispheres, the area-weighted mean of five walls of 0.6 and the lamp's 0.5,
  // (5 x 0.6 + 0.5) / 6 = 0.583.
  for (size_t k = 3; k < s.residuals.size(); ++k)
    EXPECT_NEAR(s.residuals[k] / s.residuals[k - 1], 0.58, 0.05) << k;
}

TEST(VoxelSolver, StopsOnceTheLightStillBouncingIsBelowTheTolerance) {
  // The defaults: until the light the last iteration added is below 1e-3 of the light put in,
  // at most 100 iterations. It falls by 0.58 an iteration here (above): about 13 of them.
  CoarseLampRoom room = coarseLampRoom(1.0f, 16.0f);
  const VoxelSolution s = solveVoxelRadiosity(room.scene, room.grid, room.settings);
  EXPECT_TRUE(s.converged);
  ASSERT_GE(s.residuals.size(), 2u);
  EXPECT_LT(s.residuals.back(), 1e-3);
  EXPECT_GE(s.residuals[s.residuals.size() - 2], 1e-3);  // the first iteration below it
  EXPECT_LT(s.residuals.size(), 20u);
  // With tolerance 0, the count of iterations: all of them, and no tolerance met.
  room.settings.tolerance = 0.0;
  room.settings.iterations = 3;
  const VoxelSolution counted = solveVoxelRadiosity(room.scene, room.grid, room.settings);
  EXPECT_EQ(counted.residuals.size(), 3u);
  EXPECT_FALSE(counted.converged);
}

TEST(VoxelSolver, CapAboveTheToleranceIsNotConvergedAndWarns) {
  // A closed cube of reflectance 0.999 (a glTF's 1) lit by one face: its light bounces about
  // 1 / (1 - rho) = 1000 times, so five iterations leave nearly all of it bouncing (each
  // residual about rho times the one before).
  SceneBuilder b("room");
  const uint32_t wall = b.addMaterial({"wall", Color(1.0f), Color(0.0f), false});
  const uint32_t lamp = b.addMaterial({"lamp", Color(1.0f), Color(1.0f), false});
  test::addInwardCube(b, [&](int face) { return face == 3 ? lamp : wall; });
  const Scene scene = b.build();
  VoxelRadiositySettings settings;
  settings.voxelSize = 1.0f / 16.0f;
  settings.sphereRadius = 6;
  settings.directSamples = 4;
  settings.iterations = 5;
  const VoxelRadiosity solution(scene, settings);
  const VoxelRadiosityStats& stats = solution.stats();
  EXPECT_FALSE(stats.converged);
  ASSERT_EQ(stats.residuals.size(), 5u);
  // Measured 0.483 after the first, 0.481 after the fifth.
  EXPECT_GT(stats.residuals.back(), 0.4);
  EXPECT_GT(stats.residuals.back(), 0.99 * stats.residuals.front());
  ASSERT_FALSE(stats.warnings.empty());
  const std::string& w = stats.warnings.back();
  EXPECT_NE(w.find("voxel solve not converged"), std::string::npos) << w;
  EXPECT_NE(w.find("after 5 iterations (--iterations 5), above --tolerance 0.001"),
            std::string::npos)
      << w;
  EXPECT_NE(w.find("up to 0.999"), std::string::npos) << w;
}

// A two-sided box (walls with an inside and an outside) around a lamp, above a floor, the box
// and lamp turned by `turn` about the box's centre: the light leaving the outside sides and the
// floor (their B A) must stay within `leak` of the lamp's power, with or without the first shot.
void expectLightStaysInTheBox(const glm::mat3& turn, double leak) {
  SceneBuilder b("boxed");
  const uint32_t wall = b.addMaterial({"wall", Color(0.8f), Color(0.0f), true});
  const uint32_t lamp = b.addMaterial({"lamp", Color(0.5f), Color(5.0f), false});
  const uint32_t ground = b.addMaterial({"ground", Color(0.8f), Color(0.0f), false});
  const Vec3 centre(0.5f);
  addTurnedCube(b, centre, 1.0f, turn, true, wall, b.addObject("box"));
  std::array<Vec3, 4> lampQuad = test::axisSquare(Vec3(0.0f, 0.3f, 0.0f), 1, 0.3f);
  for (Vec3& p : lampQuad) p = centre + turn * p;
  const uint32_t lampObject = b.addObject("lamp");
  test::addQuadFacing(b, lampQuad, turn * Vec3(0, -1, 0), lamp, lampObject);
  const uint32_t floorObject = b.addObject("floor");
  test::addQuadFacing(b, test::axisSquare(Vec3(0.5f, -0.4f, 0.5f), 1, 3.0f), Vec3(0, 1, 0), ground,
                      floorObject);
  const Scene scene = b.build();
  const VoxelGrid grid = voxelize(scene, 1.0f / 23.0f);
  for (bool firstShot : {false, true}) {
    SCOPED_TRACE(firstShot ? "first shot" : "pure sweep");
    VoxelSolverSettings settings;
    settings.sphereRadius = 10;
    settings.iterations = 6;
    settings.directFirstShot = firstShot;
    settings.directSamples = 8;
    const VoxelSolution s = solveVoxelRadiosity(scene, grid, settings);
    double insideLight = 0.0, emitted = 0.0, leaked = 0.0;
    size_t outside = 0;
    for (size_t e = 0; e < grid.entryCount(); ++e) {
      emitted += grid.areaOf(e) * glm::pi<float>() * maxComponent(grid.materialOf(e).emission);
      const Vec3 fromCentre = glm::transpose(turn) * (grid.centroidOf(e) - centre);
      const bool onFloor = grid.objectOf(e) == floorObject;
      const bool facesOut = glm::dot(grid.unitNormal(e), grid.centroidOf(e) - centre) > 0.0f &&
                            grid.objectOf(e) != lampObject;
      const bool wallSide = glm::compMax(glm::abs(fromCentre)) > 0.45f;
      if (onFloor || (wallSide && facesOut)) {
        ++outside;
        leaked += grid.areaOf(e) * maxComponent(s.radiosity[e]);
        if (leak == 0.0) {
          const Vec3 c = grid.centroidOf(e);
          ASSERT_EQ(maxComponent(s.radiosity[e]), 0.0f)
              << "entry " << e << " at " << c.x << "," << c.y << "," << c.z;
        }
      } else if (wallSide) {
        insideLight += maxComponent(s.radiosity[e]);
      }
    }
    EXPECT_LE(leaked, leak * emitted);
    EXPECT_GT(outside, 1000u);
    EXPECT_GT(insideLight, 0.0);
  }
}

TEST(VoxelSolver, LightInsideClosedBoxDoesNotLeak) {
  expectLightStaysInTheBox(glm::mat3(1.0f), 0.0);
}

TEST(VoxelSolver, LightInsideATurnedBoxLeaksLittle) {
  // No face along the grid. A known limit, bounded here: sides know their planes, not their
  // polygons, beyond what the sides of a voxel and of its neighbours tell. A discrete line that
  // crosses the shell near an edge, at a voxel of the face around the corner from where its ray
  // crosses, can meet that face's plane from the inside. 0.109% of the lamp's power leaves the
  // box without the first shot, 0.073% with it (measured at 57e4bb8; 0.17% and 0.12% when the
  // neighbours' folds came in): 2.4% and 1.5% while sides at an angle were told apart by the
  // plane tolerance, 1.0% and 0.65% while folds bounded only the sides of their own voxel. An
  // axis-aligned box, whose faces fill their voxels alike, leaks nothing (above).
  expectLightStaysInTheBox(oddTurn(), 0.0025);
}

TEST(VoxelSolver, SameBitForBitWhateverTheThreadCount) {
  CoarseLampRoom room = coarseLampRoom(2.0f, 16.0f);
  room.settings.iterations = 3;
  auto solve = [&](int threads) {
    tbb::task_arena arena(threads);
    return arena.execute(
        [&] { return solveVoxelRadiosity(room.scene, room.grid, room.settings).radiosity; });
  };
  // The threads share each direction's lines, and every side sums the directions in the same
  // order: any thread count gives the same bits (and a band split at other lines, 3 threads).
  const std::vector<Color> serial = solve(1);
  for (int threads : {2, 3}) {
    const std::vector<Color> parallel = solve(threads);
    ASSERT_EQ(parallel.size(), serial.size());
    for (size_t e = 0; e < serial.size(); ++e)
      ASSERT_EQ(parallel[e], serial[e]) << threads << " threads, side " << e;
  }
}

TEST(VoxelSolver, RadiosityScalesWithTheEmissionWhateverItsUnits) {
  // Radiosity is linear in the emission. The sweeps carry radiosity in half floats, whose range
  // (2^-14 to 65504) a bright lamp or a scene in other units leaves: multiplied by 2^24 the
  // lamp's radiosity is 2^24 pi 2 = 1e8 (it overflowed to infinity), and by 2^-36 every value
  // lies below 2^-30 (it flushed to zero). Scaled by a power of two, the answer must be the
  // same to rounding.
  for (bool firstShot : {false, true}) {
    SCOPED_TRACE(firstShot ? "first shot" : "pure sweep");
    auto solve = [&](float scale) {
      CoarseLampRoom room = coarseLampRoom(2.0f * scale, 12.0f);
      room.settings.iterations = 3;
      room.settings.directFirstShot = firstShot;
      return solveVoxelRadiosity(room.scene, room.grid, room.settings).radiosity;
    };
    const std::vector<Color> unit = solve(1.0f);
    for (float scale : {0x1p24f, 0x1p-36f}) {
      const std::vector<Color> scaled = solve(scale);
      ASSERT_EQ(scaled.size(), unit.size());
      double lit = 0.0;
      for (size_t e = 0; e < unit.size(); ++e)
        for (int c = 0; c < 3; ++c) {
          const float expected = unit[e][c] * scale;
          ASSERT_NEAR(scaled[e][c], expected, 1e-5f * std::abs(expected)) << scale << " side " << e;
          lit += unit[e][c];
        }
      EXPECT_GT(lit, 0.0);
    }
  }
}

// The solver refuses a grid that would not fit from this estimate, made before it allocates:
// it must cover what the solve then holds, and not by so much that it refuses grids that fit.
TEST(VoxelSolver, MemoryKnownBeforehandCoversTheSolve) {
  SceneBuilder b("room");
  const uint32_t wall = addLampRoom(b, 2.0f);
  test::addSphere(b, Vec3(0.1f), 0.3f, false, wall, b.addObject("sphere"));
  const Scene scene = b.build();
  const VoxelGrid grid = voxelize(scene, 1.0f / 24.0f);
  for (bool firstShot : {true, false}) {
    VoxelSolverSettings settings;
    settings.sphereRadius = 5;
    settings.iterations = 1;
    settings.directSamples = 2;
    settings.directFirstShot = firstShot;
    const uint64_t estimate = voxelSolveBytes(grid, settings);
    const VoxelSolution solution = solveVoxelRadiosity(scene, grid, settings);
    EXPECT_GE(estimate, solution.workingBytes);
    // The estimate's slack is the bound of the widest direction's line table (over any line
    // shift) and a deferred batch for every thread, whether it ran or not: measured 1.10x here;
    // 1.5x would refuse grids that fit in two thirds of the memory.
    EXPECT_LE(double(estimate), 1.5 * double(solution.workingBytes));
  }
}

TEST(VoxelSolver, RefusesBeforeItAllocatesWhatTheProcessMayNotHold) {
  // Under an address-space limit (ulimit -v) leaving 1 MB, a solve that needs more must be an
  // input error before it allocates its arrays, not a std::bad_alloc (or a kill) hours in.
  const Scene scene = test::uniformCube(Color(0.5f), Color(1.0f));
  const VoxelGrid grid = voxelize(scene, 1.0f / 100.0f);
  VoxelSolverSettings settings;
  settings.sphereRadius = 12;
  settings.iterations = 1;
  settings.directSamples = 1;
  constexpr uint64_t kLeft = 1u << 20;
  ASSERT_GT(voxelSolveBytes(grid, settings), 2 * kLeft);  // 6 x 100^2 sides, 4.4 MB
  const RayCaster caster(scene);                          // made with the scene, before the solve
  bool refused = false;
  {
    const test::AddressSpaceLimit limit(kLeft);
    if (limit.alreadyBelow()) GTEST_SKIP() << "the address space is already limited below 1 MB";
    ASSERT_TRUE(limit.lowered());
    try {
      solveVoxelRadiosity(scene, grid, caster, scene.lights, settings);
    } catch (const InputError&) {
      refused = true;
    } catch (const std::bad_alloc&) {
    }
  }
  EXPECT_TRUE(refused);
  // With the limit lifted the same solve runs.
  EXPECT_EQ(solveVoxelRadiosity(scene, grid, settings).radiosity.size(), grid.entryCount());
}

TEST(VoxelSolver, RefusesAGridWithMoreLinesThanTheSweepCanNumber) {
  // Two 2 mm squares 30 m apart in voxels of 1 mm: a handful of voxels in a box 30,000 voxels
  // wide, across which the diagonal (1, 1, 1) has X Y + Y Z + Z X - X - Y - Z + 1, about 2.7e9,
  // lines: more than the sweep's 32-bit line numbers hold. An input error naming the remedy,
  // before any allocation (checked while the line records were sized by the box's
  // cross-section, 16 GB a thread: without the limit a one-thread solve ran, 16 GB resident, 43 s
  // for 14 voxels, its line numbers past 2^31).
  SceneBuilder b("far apart");
  const uint32_t lamp = b.addMaterial({"lamp", Color(0.5f), Color(1.0f), false});
  const uint32_t grey = b.addMaterial({"grey", Color(0.5f), Color(0.0f), false});
  test::addQuadFacing(b, test::axisSquare(Vec3(0.0f), 0, 0.002f), Vec3(1, 0, 0), lamp,
                      b.addObject("lamp"));
  test::addQuadFacing(b, test::axisSquare(Vec3(30.0f), 0, 0.002f), Vec3(-1, 0, 0), grey,
                      b.addObject("far"));
  const Scene scene = b.build();
  const VoxelGrid grid = voxelize(scene, 0.001f);
  ASSERT_GT(grid.dims.x, 30000);
  VoxelSolverSettings settings;
  settings.sphereRadius = 2;  // holds (1, 1, 1)
  settings.iterations = 1;
  try {
    solveVoxelRadiosity(scene, grid, settings);
    ADD_FAILURE() << "solved a grid of more lines than the sweep can number";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("lines cross the grid"), std::string::npos) << message;
    EXPECT_NE(message.find("use a larger voxel size"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace rad
