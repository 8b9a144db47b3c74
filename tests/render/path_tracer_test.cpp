// The reference path tracer's images against closed forms.
#include <gtest/gtest.h>
#include <radiosity/error.h>
#include <radiosity/path_tracer.h>
#include <radiosity/scene_loader.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <filesystem>
#include <glm/gtc/constants.hpp>

#include "render/test_scenes.h"

namespace rad {
namespace {

using test::addInwardCube;
using test::addQuadFacing;
using test::axisSquare;

constexpr float kPi = glm::pi<float>();

// Every face of a closed cube emits Ke and reflects rho, all facing inward.
Scene furnace(const Color& ke, float rho) {
  SceneBuilder b("furnace");
  Material m;
  m.rho = Color(rho);
  m.emission = ke;
  const uint32_t id = b.addMaterial(m);
  addInwardCube(b, [&](int) { return id; });
  return b.build();
}

Camera insideCube(int size) {
  Camera c;
  c.eye = Vec3(0.5f, 0.45f, 0.6f);
  c.target = Vec3(0.3f, 0.5f, 0.0f);
  c.fovDeg = 120.0f;  // sees the back wall and parts of four others, edges and corners included
  c.width = c.height = size;
  return c;
}

TEST(PathTracer, WhiteFurnaceRadianceIsKeOverOneMinusRho) {
  // docs/references.md 3.2: B = E / (1 - rho) everywhere, so every pixel sees Ke / (1 - rho).
  const Color ke(1.0f, 0.5f, 0.25f);
  const float rho = 0.5f;
  PathTracerSettings settings;
  settings.samplesPerPixel = 16384;
  const PathTracedImage result = renderPathTraced(furnace(ke, rho), insideCube(8), settings);
  const Color expected = ke / (1.0f - rho);
  double worst = 0.0;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      for (int k = 0; k < 3; ++k) {
        const double error = std::abs(result.image.at(x, y)[k] / expected[k] - 1.0);
        worst = std::max(worst, error);
        EXPECT_LT(error, 0.01) << "pixel " << x << "," << y << " channel " << k;
      }
  RecordProperty("worst_relative_error", std::to_string(worst));
  std::printf("furnace: worst pixel relative error %.4f at 16384 spp\n", worst);
  EXPECT_EQ(result.stats.paths, 8u * 8u * 16384u);
  EXPECT_GT(result.stats.rays, 2 * result.stats.paths);  // at least a hit and a shadow ray each
}

// A square plane of side 1000 at y = 0 facing +y (rho 0.5), a camera 3 above looking down.
Scene plane(const Light& light) {
  SceneBuilder b("plane");
  Material m;
  m.rho = Color(0.5f);
  const uint32_t id = b.addMaterial(m);
  addQuadFacing(b, axisSquare(Vec3(0.0f), 1, 1000.0f), Vec3(0, 1, 0), id, b.addObject("plane"));
  Scene s = b.build();
  s.lights.push_back(light);
  return s;
}

constexpr int kSize = 65;

Camera lookDown() {
  Camera c;
  c.eye = Vec3(0, 3, 0);
  c.target = Vec3(0, 0, 0);
  c.up = Vec3(0, 0, -1);
  c.fovDeg = 90.0f;
  c.width = c.height = kSize;
  return c;
}

// The plane points a pixel covers, on an n x n grid: with eye (0,3,0), forward -y, right +x and
// image-up -z, a tan(45 deg) = 1 half-extent maps pixel (x, y) to x' = 3 sx and z' = -3 sy.
template <class F>
void forPixelFootprint(int x, int y, int n, F f) {
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const float sx = 2.0f * (x + (i + 0.5f) / n) / kSize - 1.0f;
      const float sy = 1.0f - 2.0f * (y + (j + 0.5f) / n) / kSize;
      f(Vec3(3.0f * sx, 0.0f, -3.0f * sy));
    }
}

// Radiance leaving a rho = 0.5 plane lit by intensity I at (0, 1, 0): rho I cos / (pi d^2),
// with cos = 1 / d (docs/references.md 3.5; units: docs/ARCHITECTURE.md "Units and conventions").
float pointLitRadiance(const Vec3& p, float intensity) {
  const Vec3 d = Vec3(0, 1, 0) - p;
  const float d2 = glm::dot(d, d);
  return 0.5f * intensity * (1.0f / std::sqrt(d2)) / (kPi * d2);
}

TEST(PathTracer, PointLightOverPlaneMatchesInverseSquareCosine) {
  Light light;
  light.type = LightType::Point;
  light.position = Vec3(0, 1, 0);
  light.intensity = Color(10.0f, 5.0f, 2.0f);
  PathTracerSettings settings;
  settings.samplesPerPixel = 256;
  const PathTracedImage result = renderPathTraced(plane(light), lookDown(), settings);
  double worst = 0.0;
  for (int y = 0; y < kSize; y += 4)
    for (int x = 0; x < kSize; x += 4) {
      double expected = 0.0;
      forPixelFootprint(x, y, 8, [&](const Vec3& p) { expected += pointLitRadiance(p, 1.0f); });
      expected /= 64.0;
      for (int k = 0; k < 3; ++k) {
        const double error =
            std::abs(result.image.at(x, y)[k] / (expected * light.intensity[k]) - 1.0);
        worst = std::max(worst, error);
        EXPECT_LT(error, 0.02) << "pixel " << x << "," << y << " channel " << k;
      }
    }
  std::printf("point light: worst pixel relative error %.4f at 256 spp\n", worst);
}

TEST(PathTracer, SpotLightDarkOutsideOuterConeAndPointLikeInsideInner) {
  Light spot;
  spot.type = LightType::Spot;
  spot.position = Vec3(0, 1, 0);
  spot.direction = Vec3(0, -1, 0);
  spot.intensity = Color(8.0f);
  spot.innerAngleDeg = 20.0f;
  spot.outerAngleDeg = 30.0f;
  PathTracerSettings settings;
  settings.samplesPerPixel = 64;
  const PathTracedImage result = renderPathTraced(plane(spot), lookDown(), settings);
  int inside = 0, outside = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      float minAngle = 180.0f, maxAngle = 0.0f;
      double expected = 0.0;
      forPixelFootprint(x, y, 8, [&](const Vec3& p) {
        const float angle = glm::degrees(std::atan(std::hypot(p.x, p.z)));  // height 1
        minAngle = std::min(minAngle, angle);
        maxAngle = std::max(maxAngle, angle);
        expected += pointLitRadiance(p, 8.0f) / 64.0;
      });
      const float value = result.image.at(x, y).g;
      if (minAngle > 30.0f) {
        ++outside;
        EXPECT_EQ(value, 0.0f) << "pixel " << x << "," << y;
      } else if (maxAngle < 20.0f) {
        ++inside;
        EXPECT_NEAR(value / expected, 1.0, 0.02) << "pixel " << x << "," << y;
      }
    }
  EXPECT_GT(inside, 20);  // the inner cone covers about 49 pixels, 37 of them entirely
  EXPECT_GT(outside, 1000);
}

// A one-sided emitter above a floor: facing up (away from the floor) or down toward it.
Scene emitterOverFloor(bool facingFloor) {
  SceneBuilder b("one-sided emitter");
  Material floor;
  floor.rho = Color(0.5f);
  Material lamp;
  lamp.rho = Color(0.0f);
  lamp.emission = Color(2.0f);
  const uint32_t floorId = b.addMaterial(floor), lampId = b.addMaterial(lamp);
  addQuadFacing(b, axisSquare(Vec3(0.5f, 0, 0.5f), 1, 1.0f), Vec3(0, 1, 0), floorId,
                b.addObject("floor"));
  addQuadFacing(b, axisSquare(Vec3(0.5f, 1, 0.5f), 1, 0.5f), Vec3(0, facingFloor ? -1 : 1, 0),
                lampId, b.addObject("lamp"));
  return b.build();
}

Camera viewFrom(const Vec3& eye, const Vec3& target) {
  Camera c;
  c.eye = eye;
  c.target = target;
  c.up = Vec3(0, 0, -1);
  c.fovDeg = 20.0f;
  c.width = c.height = 8;
  return c;
}

TEST(PathTracer, BackOfOneSidedEmitterIsDarkAndLightsNothing) {
  PathTracerSettings settings;
  settings.samplesPerPixel = 16;
  const Camera atFloor = viewFrom(Vec3(0.5f, 0.6f, 0.5f), Vec3(0.5f, 0, 0.5f));
  const Camera atLampFromBelow = viewFrom(Vec3(0.5f, 0.6f, 0.5f), Vec3(0.5f, 1, 0.5f));
  const Scene away = emitterOverFloor(false), toward = emitterOverFloor(true);
  for (const Color& c : renderPathTraced(away, atFloor, settings).image.pixels)
    EXPECT_EQ(maxComponent(c), 0.0f);
  for (const Color& c : renderPathTraced(away, atLampFromBelow, settings).image.pixels)
    EXPECT_EQ(maxComponent(c), 0.0f);
  // The same lamp turned toward the floor lights it and shows its emission (Ke = 2).
  for (const Color& c : renderPathTraced(toward, atFloor, settings).image.pixels)
    EXPECT_GT(c.g, 0.01f);
  for (const Color& c : renderPathTraced(toward, atLampFromBelow, settings).image.pixels)
    EXPECT_NEAR(c.g, 2.0f, 1e-5f);
}

TEST(PathTracer, SameSeedSameImageWithOneOrTwoThreads) {
  PathTracerSettings settings;
  settings.samplesPerPixel = 8;
  const Scene scene = furnace(Color(1.0f), 0.7f);
  const Camera camera = insideCube(40);  // several 16 x 16 tiles, some partial
  PathTracedImage one, two;
  tbb::task_arena(1).execute([&] { one = renderPathTraced(scene, camera, settings); });
  tbb::task_arena(2).execute([&] { two = renderPathTraced(scene, camera, settings); });
  EXPECT_EQ(one.image.pixels, two.image.pixels);
  EXPECT_EQ(one.stats.rays, two.stats.rays);
  settings.seed = 2;
  EXPECT_NE(renderPathTraced(scene, camera, settings).image.pixels, one.image.pixels);
}

TEST(PathTracer, ProgressReportsAndCancels) {
  PathTracerSettings settings;
  settings.samplesPerPixel = 2;
  const Scene scene = furnace(Color(1.0f), 0.5f);
  const Camera camera = insideCube(64);
  std::vector<double> fractions;
  renderPathTraced(scene, camera, settings, [&](double f) {
    fractions.push_back(f);
    return true;
  });
  ASSERT_FALSE(fractions.empty());
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_DOUBLE_EQ(fractions.back(), 1.0);
  EXPECT_THROW(renderPathTraced(scene, camera, settings, [](double) { return false; }), Cancelled);
}

TEST(PathTracer, RejectsBadSettings) {
  PathTracerSettings settings;
  settings.samplesPerPixel = 0;
  EXPECT_THROW(renderPathTraced(furnace(Color(1.0f), 0.5f), insideCube(4), settings), InputError);
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

// Stopped (as Ctrl-C does) half way, a render keeps its finished tiles; rendered again, it
// renders only the rest and makes the picture of a render never stopped, bit for bit (each tile
// has its own random stream). The checkpoint goes once the picture is done.
TEST(PathTracerCheckpoint, AStoppedRenderGoesOnToTheSamePicture) {
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / "radiosity_render_checkpoint";
  std::filesystem::remove_all(dir);
  const Scene scene = loadScene("cornell");
  Camera camera = scene.cameraOrDefault();
  camera.width = camera.height = 64;  // 16 tiles
  PathTracerSettings settings;
  settings.samplesPerPixel = 16;
  settings.checkpointDir = dir.string();
  bool stopped = false;
  try {
    renderPathTraced(scene, camera, settings, [](double f) { return f < 0.5; });
  } catch (const Cancelled& e) {
    stopped = true;
    EXPECT_NE(std::string(e.what()).find("tiles finished are kept"), std::string::npos) << e.what();
  }
  ASSERT_TRUE(stopped);
  const PathTracedImage resumed = renderPathTraced(scene, camera, settings);
  EXPECT_GE(resumed.stats.resumedTiles, 4u);
  EXPECT_LT(resumed.stats.resumedTiles, 16u);
  EXPECT_TRUE(resumed.stats.warnings.empty());
  settings.checkpointDir.clear();
  const PathTracedImage whole = renderPathTraced(scene, camera, settings);
  EXPECT_EQ(resumed.image.pixels, whole.image.pixels);
  EXPECT_TRUE(std::filesystem::is_empty(dir));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rad
