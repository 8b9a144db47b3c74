// Directional lights (the sun) in every method: a floor lit at a slant receives E cos(theta)
// everywhere nothing shadows it, and an occluder casts its parallel projection, so the floor's
// mean irradiance is E cos(theta) (A_floor - A_occluder) / A_floor. Closed forms, stated per test.
#include <gtest/gtest.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/path_tracer.h>
#include <radiosity/voxel_radiosity.h>

#include <array>
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

// The sun through a roof opening onto a floor (CIE 171:2006's daylight cases in their simplest
// form): a 1 x 1 hole in a black roof 2 units above a black 4 x 4 floor, the light at 30 degrees.
// The roof is wide enough that no floor point sees past its edge, so the floor's light is the
// hole's parallel projection alone: a 1 x 1 patch at E cos 30, moved 2 tan 30 along x, wholly on
// the floor; its mean E cos 30 / 16. Black surfaces: no bounce (and nothing for the patch
// solvers to iterate on: their answer is the direct light, which they once left at zero).
TEST(DirectionalLight, TheSunThroughARoofOpeningLightsItsProjection) {
  const Color e(4.0f);
  SceneBuilder b("roof opening");
  const uint32_t black = b.addMaterial({"black", Color(0.0f), Color(0.0f), false});
  const uint32_t floor = b.addObject("floor"), roof = b.addObject("roof");
  test::addQuadFacing(b, test::axisSquare(Vec3(0.0f), 1, 4.0f), Vec3(0, 1, 0), black, floor);
  // The roof, [-5, 5]^2 at y = 2 less [-0.5, 0.5]^2: four pieces around the hole, facing down.
  const float y = 2.0f;
  const std::array<std::array<float, 4>, 4> pieces = {
      {{-5, 5, 0.5f, 5}, {-5, 5, -5, -0.5f}, {-5, -0.5f, -0.5f, 0.5f}, {0.5f, 5, -0.5f, 0.5f}}};
  for (const auto& [x0, x1, z0, z1] : pieces)
    test::addQuadFacing(b, {Vec3(x0, y, z0), Vec3(x1, y, z0), Vec3(x1, y, z1), Vec3(x0, y, z1)},
                        Vec3(0, -1, 0), black, roof);
  b.scene().lights.push_back(sunAt(30.0f, e));
  const Scene scene = b.build();
  const double cos30 = std::cos(std::numbers::pi / 6.0), floorMean = 4.0 * cos30 / 16.0;

  const PatchRadiosity patch(scene, test::uncachedPatchSettings(1600));
  EXPECT_NEAR(test::objectNamed(patch, "floor").meanIrradiance.g, floorMean, 0.01 * floorMean);
  const VoxelRadiosity voxel(scene, smallVoxelSettings());
  EXPECT_NEAR(test::objectNamed(voxel, "floor").meanIrradiance.g, floorMean, 0.03 * floorMean);
  const std::map<std::string, ObjectRadiometry> traced = test::tracedObjectMeans(scene, 4000, 1, 1);
  EXPECT_NEAR(traced.at("floor").meanIrradiance.g, floorMean, 0.03 * floorMean);
  // The lit square's centre, at x = 2 tan 30 = 1.155, gets E cos 30; beside it, nothing.
  const SurfaceHit lit{Vec3(1.155f, 0.0f, 0.0f), Vec3(0, 1, 0), 0, true};
  const SurfaceHit dark{Vec3(0.0f, 0.0f, 0.0f), Vec3(0, 1, 0), 0, true};
  EXPECT_NEAR(patch.irradiance(lit).g, 4.0 * cos30, 0.01 * 4.0 * cos30);
  EXPECT_EQ(patch.irradiance(dark).g, 0.0f);
}

}  // namespace
}  // namespace rad
