// Pictures keep a texture's detail: the radiosity methods take the albedo per pixel from the
// texture and multiply it with their smooth irradiance (the lightmap way). A 1 m floor under a
// point light, textured with a checker of 4 x 4 squares (tests/data/scene/textured/checker.png:
// 16 x 16 texels, white and sRGB (120, 0, 0)), against rho(uv) E / pi with E = I h / d^3 there,
// the floor alone so that E is the direct light only.
#include <gtest/gtest.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/scene_builder.h>
#include <radiosity/surface_radiance.h>
#include <radiosity/texture.h>
#include <radiosity/voxel_radiosity.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>

namespace rad {
namespace {

constexpr float kHeight = 1.0f, kIntensity = 1.0f, kFactor = 0.9f;

Scene checkerFloor() {
  SceneBuilder b("checker floor");
  Material m{"checker", Color(kFactor)};
  m.rhoTexture.texture =
      Texture::load(std::string(RADIOSITY_TEST_DATA_DIR) + "/scene/textured/checker.png");
  const uint32_t material = b.addMaterial(m);
  const uint32_t floor = b.addObject("floor");
  // u along x, v along z: the floor's (x, z) is the texture's (u, v).
  const std::array<uint32_t, 4> corners{b.addVertex(Vec3(0, 0, 0), Vec2(0, 0), "floor"),
                                        b.addVertex(Vec3(0, 0, 1), Vec2(0, 1), "floor"),
                                        b.addVertex(Vec3(1, 0, 1), Vec2(1, 1), "floor"),
                                        b.addVertex(Vec3(1, 0, 0), Vec2(1, 0), "floor")};
  b.addPolygon(corners, material, floor, "floor");
  Scene scene = b.build();
  Light light;
  light.position = Vec3(0.5f, kHeight, 0.5f);
  light.intensity = Color(kIntensity);
  scene.lights = {light};
  return scene;
}

// rho(uv) E / pi at floor point (x, z), the texture's own texel (its squares are 4 texels wide,
// so the points below, at texel centres, read one texel each).
Color expectedRadiance(const Scene& scene, float x, float z) {
  const Vec3 d = Vec3(x, 0.0f, z) - scene.lights[0].position;
  const float distance = glm::length(d);
  const float e = kIntensity * kHeight / (distance * distance * distance);
  const Color texel = scene.materials[0].rhoTexture.texture->sample(
      Vec2(x, z), 0.0f, TextureWrap::Repeat, TextureWrap::Repeat);
  return kFactor * texel * e / glm::pi<float>();
}

void expectTexturePerPoint(const Scene& scene, const SurfaceRadiance& solution, float tolerance) {
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j) {
      const float x = (float(i) + 0.5f) / 16.0f, z = (float(j) + 0.5f) / 16.0f;
      SurfaceHit hit;
      hit.point = Vec3(x, 0.0f, z);
      hit.normal = Vec3(0, 1, 0);
      hit.barycentric = scene.locateOnFace(0, hit.point, hit.triangle);
      const Color got = solution.radiance(hit), want = expectedRadiance(scene, x, z);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(got[c], want[c], tolerance * want.r) << x << ", " << z << " channel " << c;
    }
}

// 0.1 m patches, no cache.
PatchRadiosity patchSolution(const Scene& scene) {
  PatchRadiositySettings settings;
  settings.patchSize = 0.1f;
  settings.cacheDir = "";
  return PatchRadiosity(scene, settings);
}

TEST(TextureRender, PatchPicturesShowTheTexturePerPixel) {
  // 0.1 m patches against 0.25 m squares: patches straddle the squares' edges, and a patch's own
  // mean would blur them; per pixel they stay sharp, the texel times the patch's smooth
  // irradiance: within 2% but at the floor's 4 corner points (+3.0%, where a vertex holds its
  // one patch's mean of a falling irradiance).
  const Scene scene = checkerFloor();
  expectTexturePerPoint(scene, patchSolution(scene), 0.035f);
}

TEST(TextureRender, VoxelPicturesShowTheTexturePerPixel) {
  const Scene scene = checkerFloor();
  VoxelRadiositySettings settings;
  settings.targetVoxels = 4000;  // 1.6 cm voxels
  settings.sphereRadius = 4;
  settings.iterations = 1;
  const VoxelRadiosity solution(scene, settings);
  expectTexturePerPoint(scene, solution, 0.03f);
}

TEST(TextureRender, RenderedFloorShowsTheCheckerAcrossARow) {
  // Looking straight down at the floor: along a row through the middle, the pixels step between
  // the two colours at every square's edge (4 squares a side: 3 steps), the red channel alone
  // barely changing while green falls by the texture's ratio (sRGB 120, 0, 0 has no green).
  const Scene scene = checkerFloor();
  const PatchRadiosity solution = patchSolution(scene);
  Camera camera;
  camera.eye = Vec3(0.5f, 1.2f, 0.5f);
  camera.target = Vec3(0.5f, 0.0f, 0.5f);
  camera.up = Vec3(0, 0, -1);
  camera.fovDeg = 45.0f;  // sees 0.99 m: the whole floor but a sliver
  camera.width = camera.height = 96;
  SurfaceRenderSettings render;
  render.direct = DirectLightMode::Solution;
  const Image image = renderSurfaceRadiance(scene, camera, solution, render);
  int steps = 0;
  bool green = image.at(2, 36).g > 0.5f * image.at(2, 36).r;
  for (int x = 3; x < 94; ++x) {
    const Color c = image.at(x, 36);
    const bool now = c.g > 0.5f * c.r;
    if (now != green) ++steps;
    green = now;
  }
  EXPECT_EQ(steps, 3);
}

}  // namespace
}  // namespace rad
