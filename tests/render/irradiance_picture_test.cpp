// Pictures of the irradiance (SurfaceRenderSettings::irradiance, PathTracerSettings::irradiance),
// what false-colour pictures show: looking straight down on a floor under a point light of
// intensity I at height h, the centre pixel sees E = I / h^2 (the light's foot), in every method.
#include <gtest/gtest.h>
#include <radiosity/error.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/path_tracer.h>
#include <radiosity/voxel_radiosity.h>

#include "lighting/light_test_scenes.h"
#include "render/test_scenes.h"

namespace rad {
namespace {

Camera lookingDown() {
  Camera c;
  c.eye = Vec3(0.0f, 4.0f, 0.0f);
  c.target = Vec3(0.0f);
  c.up = Vec3(0.0f, 0.0f, -1.0f);
  c.fovDeg = 20.0f;
  c.width = c.height = 33;
  return c;
}

TEST(IrradiancePicture, TheFloorUnderAPointLightShowsIOverHSquared) {
  const float h = 2.0f;
  const Color intensity(8.0f, 4.0f, 2.0f);
  const Scene scene = test::floorUnderLight(3.0f, test::pointLight(Vec3(0, h, 0), intensity));
  const Color expected = intensity / (h * h);
  SurfaceRenderSettings settings;
  settings.samplesPerPixel = 1;
  settings.irradiance = true;
  const PatchRadiosity patch(scene, test::uncachedPatchSettings(400));
  VoxelRadiositySettings voxelSettings;
  voxelSettings.targetVoxels = 20000;
  voxelSettings.sphereRadius = 8;
  voxelSettings.keepDirectLight = true;
  const VoxelRadiosity voxel(scene, voxelSettings);
  for (const SurfaceRadiance* solution :
       {static_cast<const SurfaceRadiance*>(&patch), static_cast<const SurfaceRadiance*>(&voxel)}) {
    const Image image = renderSurfaceRadiance(scene, lookingDown(), *solution, settings);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(image.at(16, 16)[c], expected[c], 1e-3 * expected[c]);
  }
  PathTracerSettings traced;
  traced.samplesPerPixel = 1;
  traced.irradiance = true;
  const Image image = renderPathTraced(scene, lookingDown(), traced).image;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(image.at(16, 16)[c], expected[c], 1e-3 * expected[c]);
  // Without per-pixel direct light there is no irradiance to show: refused, not a wrong picture.
  settings.direct = DirectLightMode::Solution;
  EXPECT_THROW(renderSurfaceRadiance(scene, lookingDown(), patch, settings), InputError);
}

// Looking up from the floor into a uniform sky: a picture of radiance shows the sky's L, one of
// the irradiance shows nothing there (no surface receives it).
TEST(IrradiancePicture, TheSkyIsNoSurface) {
  Light sky;
  sky.type = LightType::Sky;
  sky.sky.model = SkyModel::Uniform;
  sky.intensity = Color(0.5f);
  const Scene scene = test::floorUnderLight(3.0f, sky);
  Camera up = lookingDown();
  up.eye = Vec3(0.0f, 1.0f, 0.0f);
  up.target = Vec3(0.0f, 5.0f, 0.0f);
  const PatchRadiosity patch(scene, test::uncachedPatchSettings(100));
  SurfaceRenderSettings settings;
  settings.samplesPerPixel = 1;
  EXPECT_NEAR(renderSurfaceRadiance(scene, up, patch, settings).at(16, 16).g, 0.5f, 1e-6f);
  settings.irradiance = true;
  EXPECT_EQ(renderSurfaceRadiance(scene, up, patch, settings).at(16, 16).g, 0.0f);
}

}  // namespace
}  // namespace rad
