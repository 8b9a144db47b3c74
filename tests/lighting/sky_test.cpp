// Skies in every method (patch, voxel, the path tracer), each against a closed form stated where
// it is used: an open floor under a uniform sky receives pi L, under the CIE overcast sky
// 7 pi Lz / 9 (docs/references.md 5.3); through a roof opening, pi L times the configuration
// factor from the floor point to the opening (1(d), and 5.5 for the whole case).
#include <gtest/gtest.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/path_tracer.h>
#include <radiosity/sensors.h>
#include <radiosity/surface_radiance.h>
#include <radiosity/voxel_radiosity.h>

#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>

#include "light_test_scenes.h"

namespace rad {
namespace {

constexpr double kPi = std::numbers::pi;

Light skyOf(SkyModel model, const Color& radiance) {
  Light l;
  l.type = LightType::Sky;
  l.sky.model = model;
  l.intensity = radiance;
  return l;
}

VoxelRadiositySettings smallVoxelSettings() {
  VoxelRadiositySettings s;
  s.targetVoxels = 20000;
  s.sphereRadius = 8;
  return s;
}

// The overcast sky's shape (1 + 2 sin gamma) / 3: 1 at the zenith, 1/3 at the horizon, 0 below
// it; the uniform sky 1 everywhere above the horizon.
TEST(Sky, ModelsGiveTheirRelativeRadiance) {
  Sky overcast;
  overcast.model = SkyModel::CieOvercast;
  EXPECT_FLOAT_EQ(overcast.relativeRadiance(Vec3(0, 1, 0)).g, 1.0f);
  EXPECT_NEAR(overcast.relativeRadiance(glm::normalize(Vec3(1, 1, 0))).g,
              (1.0 + 2.0 * std::sqrt(0.5)) / 3.0, 1e-6);
  EXPECT_NEAR(overcast.relativeRadiance(glm::normalize(Vec3(1, 1e-6f, 0))).g, 1.0 / 3.0, 1e-5);
  EXPECT_EQ(overcast.relativeRadiance(Vec3(0, -1, 0)).g, 0.0f);
  overcast.up = Vec3(0, 0, 1);
  EXPECT_FLOAT_EQ(overcast.relativeRadiance(Vec3(0, 0, 1)).g, 1.0f);
  EXPECT_EQ(overcast.relativeRadiance(Vec3(0, 1, 0)).g, 0.0f);  // the horizon of a z-up scene
  const Sky uniform;
  EXPECT_EQ(uniform.relativeRadiance(glm::normalize(Vec3(1, 0.01f, 0))).g, 1.0f);
  EXPECT_EQ(uniform.relativeRadiance(glm::normalize(Vec3(1, -0.01f, 0))).g, 0.0f);
}

// The CIE clear sky (5.4) about a sun at 45 degrees: 1 at the zenith; at the sun, where chi = 0
// and the zenith angle is 45 degrees, (0.91 + 10 + 0.45) (1 - exp(-0.32 / cos 45)) over the
// zenith's (0.91 + 10 exp(-3 pi / 4) + 0.45 cos^2 45) (1 - exp(-0.32)) = 7.2495; black below the
// horizon. (At the sun, 10 exp(-3 chi) has a cusp: a float direction's rounding, chi ~ 4e-4,
// moves it by 0.1%.)
TEST(Sky, TheClearSkyIsBrightestAboutTheSun) {
  Sky clear;
  clear.model = SkyModel::CieClear;
  clear.towardSun = glm::normalize(Vec3(1, 1, 0));
  EXPECT_FLOAT_EQ(clear.relativeRadiance(Vec3(0, 1, 0)).g, 1.0f);
  const double atSun =
      (0.91 + 10.0 + 0.45) * (1.0 - std::exp(-0.32 / std::sqrt(0.5))) /
      ((0.91 + 10.0 * std::exp(-3.0 * kPi / 4.0) + 0.45 * 0.5) * (1.0 - std::exp(-0.32)));
  EXPECT_NEAR(clear.relativeRadiance(clear.towardSun).g, atSun, 2e-3 * atSun);
  EXPECT_NEAR(atSun, 7.2495, 1e-4);
  EXPECT_LT(clear.relativeRadiance(glm::normalize(Vec3(-1, 1, 0))).g, 1.0f);  // away from the sun
  EXPECT_EQ(clear.relativeRadiance(Vec3(0, -1, 0)).g, 0.0f);
}

// An environment map of 64 x 32 texels: its middle column looks along forward (-z), those to the
// right along forward x up (+x); rows go by polar angle, the lower half unused. A map whose rows
// hold the overcast sky's shape at their middle polar angle lights an open floor with the sum
// over the upper rows of value x pi (sin^2 theta1 - sin^2 theta0), the band's integral of cos
// (5.3's 7 pi / 9 less the rows' discretization).
TEST(Sky, AnEnvironmentMapLightsByItsTexels) {
  Image map(64, 32);
  for (int x = 0; x < 64; ++x) map.at(x, 7) = Color(x < 32 ? 2.0f : 0.5f);
  Sky sky;
  sky.model = SkyModel::Environment;
  sky.map = std::make_shared<const Image>(map);
  // Row 7 spans polar angles 39.4 to 45 degrees: elevation 50 is 40 from the zenith.
  const float c = std::cos(glm::radians(50.0f)), sn = std::sin(glm::radians(50.0f));
  EXPECT_EQ(sky.relativeRadiance(Vec3(-c, sn, 0)).g, 2.0f);  // left of forward: -x
  EXPECT_EQ(sky.relativeRadiance(Vec3(c, sn, 0)).g, 0.5f);
  sky.forward = Vec3(0, 0, 1);  // turned half a turn
  EXPECT_EQ(sky.relativeRadiance(Vec3(-c, sn, 0)).g, 0.5f);
  EXPECT_EQ(sky.relativeRadiance(Vec3(0, -1, 0)).g, 0.0f);  // below the horizon

  double expected = 0.0;
  for (int y = 0; y < 16; ++y) {
    const double theta0 = kPi * y / 32.0, theta1 = kPi * (y + 1) / 32.0;
    const float value = float((1.0 + 2.0 * std::cos(0.5 * (theta0 + theta1))) / 3.0);
    for (int x = 0; x < 64; ++x) map.at(x, y) = Color(value);
    expected += value * kPi * (std::pow(std::sin(theta1), 2) - std::pow(std::sin(theta0), 2));
  }
  EXPECT_NEAR(expected, 7.0 * kPi / 9.0, 0.002 * expected);
  Light light = skyOf(SkyModel::Environment, Color(1.0f));
  light.sky.map = std::make_shared<const Image>(map);
  const Scene scene = test::floorUnderLight(2.0f, light);
  const PatchRadiosity patch(scene, test::uncachedPatchSettings(100));
  EXPECT_NEAR(test::objectNamed(patch, "floor").meanIrradiance.g, expected, 0.01 * expected);
  const std::map<std::string, ObjectRadiometry> traced = test::tracedObjectMeans(scene, 400, 16, 1);
  EXPECT_NEAR(traced.at("floor").meanIrradiance.g, expected, 0.01 * expected);
}

// Camera rays that leave the scene see the sky in both renderers: looking straight up past a
// floor, every pixel is the overcast sky's zenith radiance to within its (1 + 2 sin gamma) / 3
// over the field of view (sin gamma >= cos 10 degrees at the corners of a 10-degree view).
TEST(Sky, PicturesShowTheSkyWhereCameraRaysLeave) {
  const Color lz(1.0f, 2.0f, 3.0f);
  const Scene scene = test::floorUnderLight(2.0f, skyOf(SkyModel::CieOvercast, lz));
  Camera up;
  up.eye = Vec3(0, 1, 0);
  up.target = Vec3(0, 2, 0);
  up.up = Vec3(0, 0, -1);
  up.fovDeg = 10.0f;
  up.width = up.height = 4;
  PathTracerSettings settings;
  settings.samplesPerPixel = 1;
  const Image traced = renderPathTraced(scene, up, settings).image;
  const PatchRadiosity patch(scene, test::uncachedPatchSettings(100));
  const Image radiosity = renderSurfaceRadiance(scene, up, patch, {});
  for (const Image* image : {&traced, &radiosity})
    for (const Color& c : image->pixels) {
      EXPECT_NEAR(c.b, 3.0f, 0.01f);
      EXPECT_NEAR(c.r / c.b, 1.0f / 3.0f, 1e-5f);
    }
}

// An open floor sees the whole sky: E = integral of L cos over the hemisphere, pi L for a
// uniform sky; for the overcast sky, with sin gamma = cos theta, Lz / 3 (pi + 2 (2 pi / 3)) =
// 7 pi Lz / 9 (5.3). B = rho E.
TEST(Sky, AnOpenFloorReceivesTheWholeSkyInEveryMethod) {
  const Color l(3.0f, 2.0f, 1.0f);
  for (const SkyModel model : {SkyModel::Uniform, SkyModel::CieOvercast}) {
    SCOPED_TRACE(skyModelName(model));
    const Scene scene = test::floorUnderLight(2.0f, skyOf(model, l));
    const double share = model == SkyModel::Uniform ? 1.0 : 7.0 / 9.0;
    const PatchRadiosity patch(scene, test::uncachedPatchSettings(100));
    const VoxelRadiosity voxel(scene, smallVoxelSettings());
    const std::map<std::string, ObjectRadiometry> traced =
        test::tracedObjectMeans(scene, 400, 16, 1);
    for (int c = 0; c < 3; ++c) {
      const double expected = kPi * share * l[c];
      EXPECT_NEAR(test::objectNamed(patch, "floor").meanIrradiance[c], expected, 0.01 * expected);
      EXPECT_NEAR(test::objectNamed(patch, "floor").meanRadiosity[c], 0.5 * expected,
                  0.005 * expected);
      EXPECT_NEAR(test::objectNamed(voxel, "floor").meanIrradiance[c], expected, 0.03 * expected);
      EXPECT_NEAR(traced.at("floor").meanIrradiance[c], expected, 0.01 * expected);
    }
    // What falls on the scene's bounds, a flat 4 x 4 box: E times its top's area.
    EXPECT_NEAR(scene.lightPower(scene.lights[0]).g, kPi * share * l.g * 16.0,
                1e-3 * kPi * share * l.g * 16.0);
    const SurfaceHit centre{Vec3(0.0f), Vec3(0, 1, 0), 0, true};
    EXPECT_NEAR(patch.irradiance(centre).g, kPi * share * l.g, 0.01 * kPi * share * l.g);
    EXPECT_NEAR(voxel.irradiance(centre).g, kPi * share * l.g, 0.03 * kPi * share * l.g);
  }
}

// A closed 4 x 4 x 2 box, black inside, with a 1 x 1 opening in the middle of its roof, under a
// uniform sky L (5.5): a floor point receives pi L F, F its configuration factor to the opening
// (1(d), a point under a parallel rectangle at height 2); the floor's mean is pi L times F's mean
// over the floor (a 400 x 400 midpoint rule of the closed form). All that enters, pi L times the
// opening's area, lands on the black floor and walls.
Scene roofOpeningBox(const Light& sky) {
  SceneBuilder b("roof opening");
  const uint32_t black = b.addMaterial({"black", Color(0.0f), Color(0.0f), false});
  const uint32_t floor = b.addObject("floor"), walls = b.addObject("walls");
  const uint32_t roof = b.addObject("roof");
  test::addQuadFacing(b, test::axisSquare(Vec3(0.0f), 1, 4.0f), Vec3(0, 1, 0), black, floor);
  for (int axis : {0, 2})
    for (float side : {-2.0f, 2.0f}) {
      Vec3 centre(0.0f, 1.0f, 0.0f), inward(0.0f);
      centre[axis] = side;
      inward[axis] = -side;
      std::array<Vec3, 4> q = test::axisSquare(centre, axis, 4.0f);
      for (Vec3& p : q) p.y = p.y > 1.0f ? 2.0f : 0.0f;  // 4 wide, 2 high
      test::addQuadFacing(b, q, inward, black, walls);
    }
  const std::array<std::array<float, 4>, 4> pieces = {
      {{-2, 2, 0.5f, 2}, {-2, 2, -2, -0.5f}, {-2, -0.5f, -0.5f, 0.5f}, {0.5f, 2, -0.5f, 0.5f}}};
  for (const auto& [x0, x1, z0, z1] : pieces)
    test::addQuadFacing(b, {Vec3(x0, 2, z0), Vec3(x1, 2, z0), Vec3(x1, 2, z1), Vec3(x0, 2, z1)},
                        Vec3(0, -1, 0), black, roof);
  b.scene().lights.push_back(sky);
  return b.build();
}

double meanFloorFactor() {
  constexpr int n = 400;
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k)
      sum += test::pointToParallelRectangleF(-2.0 + 4.0 * (i + 0.5) / n, -2.0 + 4.0 * (k + 0.5) / n,
                                             -0.5, 0.5, -0.5, 0.5, 2.0);
  return sum / (double(n) * n);
}

TEST(Sky, ARoofOpeningLightsTheFloorByItsConfigurationFactor) {
  const float l = 2.0f;
  const Scene scene = roofOpeningBox(skyOf(SkyModel::Uniform, Color(l)));
  const double centre = kPi * l * test::pointToParallelRectangleF(0, 0, -0.5, 0.5, -0.5, 0.5, 2.0);
  const double floorMean = kPi * l * meanFloorFactor();
  const double entering = kPi * l * 1.0;
  const SurfaceHit atCentre{Vec3(0.0f), Vec3(0, 1, 0), 0, true};

  const PatchRadiosity patch(scene, test::uncachedPatchSettings(4000));
  EXPECT_NEAR(test::objectNamed(patch, "floor").meanIrradiance.g, floorMean, 0.01 * floorMean);
  EXPECT_NEAR(patch.irradiance(atCentre).g, centre, 0.01 * centre);
  const ObjectRadiometry walls = test::objectNamed(patch, "walls");
  EXPECT_NEAR(16.0 * test::objectNamed(patch, "floor").meanIrradiance.g +
                  walls.area * walls.meanIrradiance.g,
              entering, 0.01 * entering);

  const VoxelRadiosity voxel(scene, smallVoxelSettings());
  EXPECT_NEAR(test::objectNamed(voxel, "floor").meanIrradiance.g, floorMean, 0.03 * floorMean);
  EXPECT_NEAR(voxel.irradiance(atCentre).g, centre, 0.03 * centre);

  const std::map<std::string, ObjectRadiometry> traced =
      test::tracedObjectMeans(scene, 4000, 256, 1);
  EXPECT_NEAR(traced.at("floor").meanIrradiance.g, floorMean, 0.01 * floorMean);
}

// Sensors (sensors.h) read the sky at their points through DirectLighting: under the roof
// opening of the test above, pi L F at each point (1(d)). The rays (4,096 a point) leave 1.2% rms
// at the centre (measured here: -1.3%; 0.5 off the axis +0.3%, 1 unit up -0.9%), more where the
// opening is a smaller share of the hemisphere (F = 0.025 at (1.5, 0, -1): +6.3%).
TEST(Sky, SensorsReadTheSkyThroughTheOpening) {
  const float l = 2.0f;
  const Scene scene = roofOpeningBox(skyOf(SkyModel::Uniform, Color(l)));
  const PatchRadiosity patch(scene, test::uncachedPatchSettings(400));
  const std::vector<SensorPoint> points = {{Vec3(0.0f), Vec3(0, 1, 0)},
                                           {Vec3(0.5f, 0.0f, 0.5f), Vec3(0, 1, 0)},
                                           {Vec3(1.5f, 0.0f, -1.0f), Vec3(0, 1, 0)},
                                           {Vec3(0.0f, 1.0f, 0.0f), Vec3(0, 1, 0)}};
  const std::vector<Color> e =
      sensorIrradiance(scene, RayCaster(scene), patch, points, SensorSettings{});
  const double tolerance[] = {0.02, 0.02, 0.1, 0.02};
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i].position;
    const double expected =
        kPi * l * test::pointToParallelRectangleF(p.x, p.z, -0.5, 0.5, -0.5, 0.5, 2.0 - p.y);
    EXPECT_NEAR(e[i].g, expected, tolerance[i] * expected)
        << "at " << p.x << ", " << p.y << ", " << p.z;
  }
}

}  // namespace
}  // namespace rad
