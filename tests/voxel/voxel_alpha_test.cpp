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

// A lamp [-1, 1]^2 at z = 2 facing down over a black floor [-1, 1]^2 at z = 0, and a black
// sheet at z = 1 covering the share `alpha` (Blend), wider than both.
Scene lampOverFloor(std::optional<float> alpha) {
  SceneBuilder b("lamp over floor");
  const uint32_t lamp = b.addMaterial({"lamp", Color(0.0f), Color(1.0f)});
  const uint32_t black = b.addMaterial({"black", Color(0.0f)});
  test::addQuadFacing(b, test::axisSquare(Vec3(0, 0, 2), 2, 2.0f), Vec3(0, 0, -1), lamp,
                      b.addObject("lamp"));
  test::addQuadFacing(b, test::axisSquare(Vec3(0, 0, 0), 2, 2.0f), Vec3(0, 0, 1), black,
                      b.addObject("floor"));
  if (alpha) {
    Material sheet{"sheet", Color(0.0f)};
    sheet.alphaMode = AlphaMode::Blend;
    sheet.alpha = *alpha;
    test::addQuadFacing(b, test::axisSquare(Vec3(0, 0, 1), 2, 3.0f), Vec3(0, 0, -1),
                        b.addMaterial(sheet), b.addObject("sheet"));
  }
  return b.build();
}

double floorIrradiance(const Scene& scene, std::vector<std::string>* warnings = nullptr) {
  VoxelRadiositySettings settings;
  settings.targetVoxels = 20000;
  settings.sphereRadius = 8;
  settings.directSamples = 16;
  const VoxelRadiosity solution(scene, settings);
  if (warnings) *warnings = solution.stats().warnings;
  for (const ObjectRadiometry& o : solution.objectRadiometry())
    if (o.name == "floor") return o.meanIrradiance.g;
  ADD_FAILURE() << "no floor";
  return 0.0;
}

TEST(VoxelAlpha, FirstShotPassesOneMinusAlphaAndTheSolveSaysWhatItApproximates) {
  // Everything black: the floor's light is the first shot alone, 16 emitter samples a side (a
  // few per cent each) averaged over about 4,000 floor sides: within 2%.
  const double open = floorIrradiance(lampOverFloor({}));
  std::vector<std::string> warnings;
  const double through = floorIrradiance(lampOverFloor(0.3f), &warnings) / open;
  EXPECT_NEAR(through, 0.7, 0.02);
  std::printf("voxel, blend sheet 0.3: the floor gets %.4f of its light\n", through);
  ASSERT_FALSE(warnings.empty());
  EXPECT_NE(warnings.back().find("not opaque"), std::string::npos) << warnings.back();
  EXPECT_NEAR(floorIrradiance(lampOverFloor(0.7f)) / open, 0.3, 0.02);
}

}  // namespace
}  // namespace rad
