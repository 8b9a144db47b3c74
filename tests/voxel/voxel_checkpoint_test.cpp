// A voxel solve stopped part way goes on from its checkpoint to the very answer of a solve never
// stopped; a checkpoint that is damaged or of another grid is said so and not used.
#include "voxel/voxel_checkpoint.h"

#include <gtest/gtest.h>
#include <radiosity/error.h>
#include <radiosity/scene_loader.h>
#include <radiosity/voxel_radiosity.h>

#include <filesystem>
#include <fstream>

namespace rad {
namespace {

namespace fs = std::filesystem;

VoxelRadiositySettings checkpointed(const fs::path& dir, bool lightGroups = false) {
  VoxelRadiositySettings s;
  s.targetVoxels = 3000;
  s.sphereRadius = 8;
  s.laterSphereRadius = 5;  // a coarser sphere after the first: the weights change on resume too
  s.iterations = 5;
  s.tolerance = 0.0;  // all five: the stops below fall in given iterations
  s.directSamples = 8;
  s.lightGroups = lightGroups;
  s.checkpointDir = dir.string();
  return s;
}

// One folder per test: ctest runs tests in parallel, and two solves of the same scene and
// settings share a checkpoint's name.
fs::path freshDir(const std::string& name) {
  const std::string test = testing::UnitTest::GetInstance()->current_test_info()->name();
  const fs::path dir = fs::path(testing::TempDir()) / ("radiosity_checkpoint_" + name + "_" + test);
  fs::remove_all(dir);
  return dir;
}

void expectSameSides(const VoxelRadiosity& a, const VoxelRadiosity& b) {
  ASSERT_EQ(a.elementCount(), b.elementCount());
  for (size_t e = 0; e < a.elementCount(); ++e) {
    ASSERT_EQ(a.element(e).radiosity, b.element(e).radiosity) << "side " << e;
    ASSERT_EQ(a.element(e).irradiance, b.element(e).irradiance) << "side " << e;
  }
}

// Stopped (as Ctrl-C does) in the sweeps once `stopAt` of the progress is reached, then solved
// again: it goes on after the last whole iteration (or the first shot), and ends where an
// uninterrupted solve ends, bit for bit.
void expectStoppedSolveGoesOn(bool lightGroups, double stopAt, int resumedAtLeast) {
  const Scene scene = loadScene("cornell-spot");
  const fs::path dir = freshDir(lightGroups ? "groups" : "stop");
  const VoxelModel model(scene, checkpointed(dir, lightGroups));
  const VoxelModel plain(scene, checkpointed("", lightGroups));
  const VoxelRadiosity whole = plain.solve(scene.lights);

  // Progress runs from 0 to 1 over the first shot, then again over the sweeps (per group, in
  // its share): `stopAt` counts once the progress has gone back to start the sweeps.
  double last = 0.0;
  bool sweeping = false, stopped = false;
  try {
    model.solve(scene.lights, [&](double f) {
      sweeping = sweeping || f < last;
      last = f;
      return !(sweeping && f >= stopAt);
    });
  } catch (const Cancelled& e) {
    stopped = true;
    EXPECT_NE(std::string(e.what()).find("goes on from iteration"), std::string::npos) << e.what();
  }
  ASSERT_TRUE(stopped);
  ASSERT_FALSE(fs::is_empty(dir));
  const VoxelRadiosity resumed = model.solve(scene.lights);
  EXPECT_TRUE(resumed.stats().warnings.empty()) << resumed.stats().warnings.front();
  EXPECT_GE(resumed.stats().resumedIterations, resumedAtLeast);
  EXPECT_EQ(resumed.stats().residuals, whole.stats().residuals);
  expectSameSides(resumed, whole);
  EXPECT_TRUE(fs::is_empty(dir)) << "checkpoints outlive a finished solve";
}

// Past 80% of the sweeps lies beyond the second of five iterations (the first sweeps the finer
// sphere, so it takes the larger share).
TEST(VoxelCheckpoint, AStoppedSolveGoesOnToTheSameAnswer) {
  expectStoppedSolveGoesOn(false, 0.8, 2);
}

// Stopped in the first iteration, it goes on after the first shot.
TEST(VoxelCheckpoint, AStopInTheFirstSweepKeepsTheFirstShot) {
  expectStoppedSolveGoesOn(false, 0.05, 0);
}

// Two groups, each its share of the progress: 45% of it is late in the first group's sweeps.
TEST(VoxelCheckpoint, LightGroupsSolvedApartGoOnToo) {
  expectStoppedSolveGoesOn(true, 0.45, 1);
}

TEST(VoxelCheckpoint, ADamagedOrForeignCheckpointIsSaidSoAndNotUsed) {
  const fs::path dir = freshDir("damaged");
  VoxelCheckpoint state;
  state.iterationsDone = 1;
  state.irradiance.assign(10, Color(1.0f));
  state.bounce.assign(10, Color(0.5f));
  state.bouncePower = {Vec3d(1.0)};
  state.residuals = {0.5};
  state.iterationSeconds = {0.1};
  const fs::path file = dir / "voxel-test.checkpoint";
  ASSERT_EQ(saveVoxelCheckpoint(file, state), "");
  std::string warning;
  ASSERT_TRUE(loadVoxelCheckpoint(file, 10, warning)) << warning;
  EXPECT_FALSE(loadVoxelCheckpoint(file, 11, warning));
  EXPECT_NE(warning.find("made for another grid"), std::string::npos) << warning;
  {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(40);
    f.put('\x7f');
  }
  warning.clear();
  EXPECT_FALSE(loadVoxelCheckpoint(file, 10, warning));
  EXPECT_NE(warning.find("truncated or corrupt"), std::string::npos) << warning;
  EXPECT_NE(warning.find("solving from the start"), std::string::npos) << warning;
  fs::resize_file(file, 30);
  EXPECT_FALSE(loadVoxelCheckpoint(file, 10, warning));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rad
