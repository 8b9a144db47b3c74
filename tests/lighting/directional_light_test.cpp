// Directional lights (the sun) in every method: a floor lit at a slant receives E cos(theta)
// everywhere nothing shadows it, and an occluder casts its parallel projection, so the floor's
// mean irradiance is E cos(theta) (A_floor - A_occluder) / A_floor. Closed forms, stated per test.
#include <gtest/gtest.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/path_tracer.h>
#include <radiosity/voxel_radiosity.h>

#include <cmath>
#include <map>
#include <numbers>

#include "light_test_scenes.h"

namespace rad {
namespace {

// Light travelling down at `tiltDeg` from the vertical, leaning toward +x.
Light sunAt(float tiltDeg, const Color& irradiance) {
  Light l;
  l.type = LightType::Directional;
  const float t = tiltDeg * std::numbers::pi_v<float> / 180.0f;
  l.direction = Vec3(std::sin(t), -std::cos(t), 0.0f);
  l.intensity = irradiance;
  return l;
}

VoxelRadiositySettings smallVoxelSettings() {
  VoxelRadiositySettings s;
  s.targetVoxels = 20000;
  s.sphereRadius = 8;
  s.directSamples = 16;
  return s;
}

// Every point of a lone floor sees the light at 60 degrees: H = E cos 60 = E / 2 exactly, B = rho
// H.
TEST(DirectionalLight, AFloorReceivesECosThetaInEveryMethod) {
  const Color e(3.0f, 2.0f, 1.0f);
  const Scene scene = test::floorUnderLight(2.0f, sunAt(60.0f, e));
  const PatchRadiosity patch(scene, test::uncachedPatchSettings(100));
  const VoxelRadiosity voxel(scene, smallVoxelSettings());
  const std::map<std::string, ObjectRadiometry> traced = test::tracedObjectMeans(scene, 400, 4, 1);
  for (int c = 0; c < 3; ++c) {
    const double expected = 0.5 * e[c];
    EXPECT_NEAR(test::objectNamed(patch, "floor").meanIrradiance[c], expected, 1e-4 * expected);
    EXPECT_NEAR(test::objectNamed(patch, "floor").meanRadiosity[c], 0.5 * expected,
                1e-4 * expected);
    EXPECT_NEAR(test::objectNamed(voxel, "floor").meanIrradiance[c], expected, 0.01 * expected);
    EXPECT_NEAR(traced.at("floor").meanIrradiance[c], expected, 1e-4 * expected);
  }
  // Facing away from it, a floor is dark.
  const Scene below = test::floorUnderLight(2.0f, sunAt(120.0f, e));
  EXPECT_EQ(maxComponent(
                test::objectNamed(PatchRadiosity(below, test::uncachedPatchSettings(100)), "floor")
                    .meanIrradiance),
            0.0f);
}

// A 0.6 x 0.6 occluder 1 unit above a 4 x 4 floor, the light at 30 degrees: its shadow is the
// same square moved by tan 30 along x (parallel rays), all on the floor, so the floor receives
// E cos 30 (16 - 0.36) / 16 on average; the occluder's top E cos 30.
TEST(DirectionalLight, AnOccluderCastsItsParallelShadow) {
  const Color e(2.0f);
  const Scene scene = test::floorUnderLight(2.0f, sunAt(30.0f, e), 0.3f, 1.0f);
  const double cos30 = std::cos(std::numbers::pi / 6.0);
  const double floorMean = 2.0 * cos30 * (16.0 - 0.36) / 16.0;
  // The floor gets no bounce: the occluder faces up, with no underside to reflect onto it.
  const PatchRadiosity patch(scene, test::uncachedPatchSettings(1600));
  EXPECT_NEAR(test::objectNamed(patch, "floor").meanIrradiance.g, floorMean, 0.005 * floorMean);
  EXPECT_NEAR(test::objectNamed(patch, "occluder").meanIrradiance.g, 2.0 * cos30, 1e-4);
  const VoxelRadiosity voxel(scene, smallVoxelSettings());
  EXPECT_NEAR(test::objectNamed(voxel, "floor").meanIrradiance.g, floorMean, 0.03 * floorMean);

  // Points well inside and outside the moved shadow (its centre at x = tan 30 = 0.577).
  const float shift = float(std::tan(std::numbers::pi / 6.0));
  const SurfaceHit inside{Vec3(shift, 0.0f, 0.0f), Vec3(0, 1, 0), 0, true};
  const SurfaceHit underOccluder{Vec3(-0.25f, 0.0f, 0.0f), Vec3(0, 1, 0), 0, true};
  EXPECT_EQ(patch.radiance(inside).g, 0.0f);
  EXPECT_GT(patch.radiance(underOccluder).g, 0.0f);  // lit: the shadow fell beside it
}

}  // namespace
}  // namespace rad
