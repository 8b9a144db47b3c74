// Point, spot and IES lights in the patch method: the floor's mean irradiance against closed
// forms and independent numerical integrals, shadows where geometry puts them, and whole scenes
// against the path tracer (the voxel method's too).
#include <gtest/gtest.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/scene_loader.h>
#include <radiosity/voxel_radiosity.h>

#include <map>

#include "light_test_scenes.h"

namespace rad {
namespace {

const std::string kIesDir = std::string(RADIOSITY_TEST_DATA_DIR) + "/scene/ies/";

// Mean irradiance I Omega / A of a point light over a floor that nothing else lights: Omega by
// the corner formula (light_test_scenes.h), independent of the mesh and the shadow rays.
TEST(PatchLights, PointLightOverAFloorGivesIOmegaOverA) {
  const float half = 2.0f, height = 1.5f;
  const Color intensity(10.0f, 5.0f, 2.0f);
  const Scene scene = test::floorUnderLight(half, test::pointLight(Vec3(0, height, 0), intensity));
  const PatchRadiosity solution(scene, test::uncachedPatchSettings(400));
  const double omega = test::rectangleSolidAngle(0, 0, -half, half, -half, half, height);
  const double area = 4.0 * half * half;
  const ObjectRadiometry floor = test::objectNamed(solution, "floor");
  for (int c = 0; c < 3; ++c) {
    const double expected = intensity[c] * omega / area;
    EXPECT_NEAR(floor.meanIrradiance[c], expected, 0.01 * expected) << "channel " << c;
    // Nothing else in the scene: the floor reflects what it receives, rho = 0.5.
    EXPECT_NEAR(floor.meanRadiosity[c], 0.5 * expected, 0.005 * expected) << "channel " << c;
  }
  EXPECT_GT(solution.stats().lightRays, 0u);
}

// Off to the side and low, beyond the floor's edge: the light meets the floor at grazing angles
// over most of it (the signed corners of the closed form cover a point outside the rectangle).
TEST(PatchLights, PointLightAtATiltBeyondTheFloorsEdge) {
  const float half = 1.0f;
  const Vec3 position(2.5f, 0.8f, 0.4f);
  const Scene scene = test::floorUnderLight(half, test::pointLight(position, Color(3.0f)));
  const PatchRadiosity solution(scene, test::uncachedPatchSettings(400));
  const double omega =
      test::rectangleSolidAngle(position.x, position.z, -half, half, -half, half, position.y);
  const double expected = 3.0 * omega / (4.0 * half * half);
  EXPECT_NEAR(test::objectNamed(solution, "floor").meanIrradiance.g, expected, 0.01 * expected);
}

// A square occluder between the light and the floor casts the square shadow of the central
// projection: the floor receives I (Omega_floor - Omega_occluder) / A, patches wholly inside the
// shadow receive nothing and those wholly outside it receive light.
TEST(PatchLights, OccluderCastsItsShadowWhereGeometrySays) {
  const float half = 2.0f, height = 2.0f, occluderHalf = 0.3f, occluderHeight = 1.0f;
  const Scene scene = test::floorUnderLight(half, test::pointLight(Vec3(0, height, 0), Color(4.0f)),
                                            occluderHalf, occluderHeight);
  const PatchRadiosity solution(scene, test::uncachedPatchSettings(1600));
  const double shadowHalf = occluderHalf * height / (height - occluderHeight);  // 0.6
  const double omega =
      test::rectangleSolidAngle(0, 0, -half, half, -half, half, height) -
      test::rectangleSolidAngle(0, 0, -shadowHalf, shadowHalf, -shadowHalf, shadowHalf, height);
  const double expected = 4.0 * omega / (4.0 * half * half);
  EXPECT_NEAR(test::objectNamed(solution, "floor").meanIrradiance.g, expected, 0.01 * expected);

  // Radiance at points well inside and well outside the shadow (smooth shading interpolates
  // between patch corners, so stay a patch away from its edge). The floor is a quad face, one
  // quadtree for both of its triangles: triangle 0 locates any point of it.
  const float margin = 0.25f;
  for (float x : {-0.3f, 0.0f, 0.25f}) {
    const SurfaceHit hit{Vec3(x, 0.0f, 0.1f), Vec3(0, 1, 0), 0, true};
    EXPECT_EQ(solution.radiance(hit).g, 0.0f) << "inside the shadow at x = " << x;
  }
  for (float x : {float(shadowHalf) + margin, -float(shadowHalf) - margin, 1.5f}) {
    const SurfaceHit hit{Vec3(x, 0.0f, 0.0f), Vec3(0, 1, 0), 0, true};
    EXPECT_GT(solution.radiance(hit).g, 0.0f) << "outside the shadow at x = " << x;
  }
}

// A spot: the floor's mean irradiance against a 2000 x 2000 midpoint integral of the profile
// (written out in the test, not the library's) over the floor.
TEST(PatchLights, SpotFloorMeanMatchesTheIntegralOfItsFalloff) {
  const float half = 2.0f, height = 1.5f;
  Light spot = test::pointLight(Vec3(0.3f, height, -0.2f), Color(6.0f));
  spot.type = LightType::Spot;
  spot.direction = glm::normalize(Vec3(0.2f, -1.0f, 0.1f));
  spot.innerAngleDeg = 20.0f;
  spot.outerAngleDeg = 35.0f;
  const Scene scene = test::floorUnderLight(half, spot);
  const PatchRadiosity solution(scene, test::uncachedPatchSettings(1600));
  const Vec3d axis(spot.direction);
  const double expected =
      test::meanFloorIrradiance(half, Vec3d(spot.position), 2000, [&](const Vec3d& toward) {
        return 6.0 * test::spotFalloff(glm::dot(toward, axis), 20.0, 35.0);
      });
  EXPECT_NEAR(test::objectNamed(solution, "floor").meanIrradiance.g, expected, 0.01 * expected);
}

// An IES light (the photompy LM-63-2019 file: quadrant symmetric, falling from 10,000 cd at
// nadir) aimed down: the floor's mean irradiance against a 2000 x 2000 midpoint integral of its
// candela table (the table's interpolation is checked against the file in ies_profile_test).
TEST(PatchLights, IesFloorMeanMatchesTheIntegralOfItsCandelaTable) {
  const float half = 2.0f, height = 1.2f;
  Light ies = test::pointLight(Vec3(0.1f, height, 0.0f), Color(1e-3f));
  ies.type = LightType::Ies;
  ies.ies = std::make_shared<IesProfile>(loadIesProfile(kIesDir + "photompy_tilt_include_v19.ies"));
  const Scene scene = test::floorUnderLight(half, ies);
  const PatchRadiosity solution(scene, test::uncachedPatchSettings(1600));
  // Down the axis is the table's nadir (V = 0); H is measured in the luminaire frame, which for
  // this quadrant-symmetric table matters only through |x| and |y| of the direction.
  const double expected = test::meanFloorIrradiance(
      half, Vec3d(ies.position), 2000,
      [&](const Vec3d& toward) { return double(ies.intensityToward(Vec3(toward)).g); });
  EXPECT_NEAR(test::objectNamed(solution, "floor").meanIrradiance.g, expected, 0.02 * expected);
}

// Whole scenes: per-surface mean radiosity within a tolerance of the path tracer's (20,000
// points x 16 paths per object; the measured spread between seeds is below 0.5%).
void expectSurfaceMeansMatchThePathTracer(const Scene& scene,
                                          const std::vector<ObjectRadiometry>& solved,
                                          double tolerance) {
  const std::map<std::string, ObjectRadiometry> expected =
      test::tracedObjectMeans(scene, 20000, 16, 3);
  int compared = 0;
  for (const ObjectRadiometry& o : solved) {
    const ObjectRadiometry& ref = expected.at(o.name);
    for (int c = 0; c < 3; ++c) {
      if (ref.meanRadiosity[c] < 0.05f * maxComponent(ref.meanRadiosity)) continue;
      EXPECT_NEAR(o.meanRadiosity[c], ref.meanRadiosity[c], tolerance * ref.meanRadiosity[c])
          << o.name << " channel " << c;
      ++compared;
    }
  }
  EXPECT_GE(compared, 15);
}

std::vector<ObjectRadiometry> patchMeans(const Scene& scene) {
  PatchRadiositySettings settings;
  settings.cacheDir.clear();
  return PatchRadiosity(scene, settings).objectRadiometry();
}

// 30k voxels and R = 12: measured on cornell-spot +0.4..+3.9% per surface and channel, 1.4 s.
std::vector<ObjectRadiometry> voxelMeans(const Scene& scene) {
  VoxelRadiositySettings settings;
  settings.targetVoxels = 30000;
  settings.sphereRadius = 12;
  settings.directSamples = 16;
  return VoxelRadiosity(scene, settings).objectRadiometry();
}

Scene cornellUnderAnIesLight() {
  Scene scene = loadScene("cornell-spot");
  Light& light = scene.lights.at(0);
  light.type = LightType::Ies;
  light.ies =
      std::make_shared<IesProfile>(loadIesProfile(kIesDir + "photompy_tilt_include_v19.ies"));
  light.intensity = Color(30.0f, 20.0f, 10.0f);  // W/sr per candela: 10,000 cd at nadir
  return scene;
}

TEST(PatchLights, CornellSpotMatchesThePathTracer) {
  const Scene scene = loadScene("cornell-spot");
  expectSurfaceMeansMatchThePathTracer(scene, patchMeans(scene), 0.03);
}

TEST(PatchLights, CornellUnderAnIesLightMatchesThePathTracer) {
  const Scene scene = cornellUnderAnIesLight();
  expectSurfaceMeansMatchThePathTracer(scene, patchMeans(scene), 0.03);
}

TEST(VoxelLights, CornellSpotMatchesThePathTracer) {
  const Scene scene = loadScene("cornell-spot");
  expectSurfaceMeansMatchThePathTracer(scene, voxelMeans(scene), 0.05);
}

TEST(VoxelLights, CornellUnderAnIesLightMatchesThePathTracer) {
  const Scene scene = cornellUnderAnIesLight();
  expectSurfaceMeansMatchThePathTracer(scene, voxelMeans(scene), 0.05);
}

}  // namespace
}  // namespace rad
