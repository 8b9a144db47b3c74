// The voxel method with surfaces that are not opaque: the first shot's shadow rays pass a Blend
// sheet in the share 1 - alpha (the ray caster's coverage), so the direct light under it is
// right; the sweeps take a side as opaque or empty by its coverage (voxelizer.cpp), which the
// solve says in a warning (docs/ARCHITECTURE.md).
#include <gtest/gtest.h>
#include <radiosity/scene_builder.h>
#include <radiosity/voxel_radiosity.h>

#include <cstdio>
#include <optional>
#include <string>

#include "render/test_scenes.h"

namespace rad {
namespace {

double floorIrradiance(const Scene& scene, std::vector<std::string>* warnings = nullptr) {
  VoxelRadiositySettings settings;
  settings.targetVoxels = 20000;
  settings.sphereRadius = 8;
  settings.directSamples = 16;
  const VoxelRadiosity solution(scene, settings);
  if (warnings) *warnings = solution.stats().warnings;
  return test::objectNamed(solution, "floor").meanIrradiance.g;
}

TEST(VoxelAlpha, FirstShotPassesOneMinusAlphaAndTheSolveSaysWhatItApproximates) {
  // Everything black: the floor's light is the first shot alone, 16 emitter samples a side (a
  // few per cent each) averaged over about 4,000 floor sides: within 2%.
  const double open = floorIrradiance(test::lampOverFloor({}));
  std::vector<std::string> warnings;
  const double through = floorIrradiance(test::lampOverFloor(0.3f), &warnings) / open;
  EXPECT_NEAR(through, 0.7, 0.02);
  std::printf("voxel, blend sheet 0.3: the floor gets %.4f of its light\n", through);
  ASSERT_FALSE(warnings.empty());
  EXPECT_NE(warnings.back().find("not opaque"), std::string::npos) << warnings.back();
  EXPECT_NEAR(floorIrradiance(test::lampOverFloor(0.7f)) / open, 0.3, 0.02);
}

}  // namespace
}  // namespace rad
