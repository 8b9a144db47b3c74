// Sensors (sensors.h): irradiance at points, as a lux meter reads it, in every method, against
// the closed forms CIE 171:2006 tests lighting programs with: a point source over a plane (the
// cos^3 law), a Lambertian rectangle above a point (its configuration factor) and the
// integrating room (a closed room's mean indirect irradiance). Each reference is stated where it
// is used.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/path_tracer.h>
#include <radiosity/sensors.h>
#include <radiosity/voxel_radiosity.h>

#include <cmath>
#include <cstdio>
#include <glm/gtc/constants.hpp>
#include <vector>

#include "lighting/light_test_scenes.h"
#include "render/test_scenes.h"

namespace rad {
namespace {

VoxelRadiositySettings smallVoxelSettings() {
  VoxelRadiositySettings s;
  s.targetVoxels = 20000;
  s.sphereRadius = 8;
  return s;
}

// The relative error of a reading, printed for the validation table of docs/ARCHITECTURE.md
// ("Sensors"): `ctest -R Sensors --verbose` shows each case's, per method.
double reportedError(const std::string& what, double measured, double expected) {
  const double error = (measured - expected) / expected;
  std::printf("validation: %s: %+.3f%%\n", what.c_str(), 100.0 * error);
  return error;
}

std::vector<Color> tracedSensors(const Scene& scene, std::span<const SensorPoint> points,
                                 int paths) {
  SensorSettings sensors;
  sensors.hemisphereRays = paths;
  return estimateSensorIrradiance(scene, RayCaster(scene), points, sensors, PathTracerSettings{});
}

std::vector<Color> solvedSensors(const Scene& scene, const SurfaceSolution& solution,
                                 std::span<const SensorPoint> points) {
  return sensorIrradiance(scene, RayCaster(scene), solution, points, SensorSettings{});
}

// A point light of intensity I at height h over a floor: at a point x off its foot, facing up,
// E = I cos(theta) / d^2 = I h / (h^2 + x^2)^(3/2) (the cos^3 law); facing
// the light, E = I / d^2. The floor is black: a tilted sensor sees nothing else.
TEST(Sensors, PointSourceOverAPlaneFollowsTheCosineCubedLaw) {
  const float h = 1.5f;
  const Color intensity(4.0f, 2.0f, 1.0f);
  Scene scene = test::floorUnderLight(3.0f, test::pointLight(Vec3(0, h, 0), intensity));
  scene.materials[0].rho = Color(0.0f);
  std::vector<SensorPoint> points;
  std::vector<double> expected;
  for (float x : {0.0f, 0.5f, 1.0f, 2.0f}) {
    points.push_back({Vec3(x, 0.0f, 0.0f), Vec3(0, 1, 0)});
    expected.push_back(h / std::pow(double(h * h + x * x), 1.5));
  }
  points.push_back({Vec3(2.0f, 0.0f, 0.0f), Vec3(-2.0f, h, 0.0f) / std::hypot(2.0f, h)});
  expected.push_back(1.0 / (h * h + 4.0));

  const PatchRadiosity patch(scene, test::uncachedPatchSettings(400));
  const VoxelRadiosity voxel(scene, smallVoxelSettings());
  const std::pair<const char*, std::vector<Color>> methods[] = {
      {"patch", solvedSensors(scene, patch, points)},
      {"voxel", solvedSensors(scene, voxel, points)},
      {"path tracer", tracedSensors(scene, points, 64)}};
  for (const auto& [name, measured] : methods)
    for (size_t i = 0; i < points.size(); ++i) {
      const std::string what = fmt::format("point source, point {}, {}", i, name);
      EXPECT_LT(std::abs(reportedError(what, measured[i].r, intensity.r * expected[i])), 1e-4);
      for (int c = 1; c < 3; ++c)
        EXPECT_NEAR(measured[i][c], intensity[c] * expected[i], 1e-4 * intensity[c] * expected[i])
            << what;
    }
}

// A 2 x 2 Lambertian square of radiance Ke = 1 at height 2 above black surroundings: a point
// below it facing up receives E = pi Ke F, F the configuration factor from the point to the
// square (docs/references.md 1(d), by superposition of corner rectangles): below the centre, a
// corner, and outside the square's outline.
TEST(Sensors, ALambertianRectangleGivesPiTimesItsConfigurationFactor) {
  const Scene scene = test::lampOverFloor(std::nullopt);
  const double pi = glm::pi<double>();
  const std::vector<SensorPoint> points = {{Vec3(0.0f, 0.0f, 0.0f), Vec3(0, 0, 1)},
                                           {Vec3(1.0f, 1.0f, 0.0f), Vec3(0, 0, 1)},
                                           {Vec3(1.5f, 0.25f, 0.5f), Vec3(0, 0, 1)}};
  const double expected[] = {pi * test::pointToParallelRectangleF(0, 0, -1, 1, -1, 1, 2),
                             pi * test::cornerElementF(2, 2, 2),
                             pi * test::pointToParallelRectangleF(1.5, 0.25, -1, 1, -1, 1, 1.5)};
  const PatchRadiosity patch(scene, test::uncachedPatchSettings(400));
  const VoxelRadiosity voxel(scene, smallVoxelSettings());
  const std::vector<Color> exact[] = {solvedSensors(scene, patch, points),
                                      solvedSensors(scene, voxel, points)};
  const std::vector<Color> traced = tracedSensors(scene, points, 16384);
  const char* const names[] = {"below its centre", "below its corner", "beside it"};
  for (size_t i = 0; i < points.size(); ++i) {
    const std::string what = std::string("rectangle, ") + names[i] + ", ";
    // The radiosity methods take the square's form factor exactly (float rounding only).
    EXPECT_LT(std::abs(reportedError(what + "patch", exact[0][i].g, expected[i])), 1e-4);
    EXPECT_LT(std::abs(reportedError(what + "voxel", exact[1][i].g, expected[i])), 1e-4);
    // The path tracer samples the square: 16,384 paths a point, within 1%.
    EXPECT_LT(std::abs(reportedError(what + "path tracer", traced[i].g, expected[i])), 0.01);
  }
}

// A unit cube of reflectance rho with a point light of intensity I at its centre. Each face's
// mean irradiance is its direct light, I (4 pi / 6) / A (the face subtends a sixth of the
// sphere), plus the integrating room's indirect light, Phi rho / (S (1 - rho)) with Phi = 4 pi I
// and S = 6 (docs/references.md 3.1; every face alike by symmetry). A 16 x 16 grid of sensors at
// the floor's cell centres averages the direct light by the midpoint rule (computed here
// alike) and the smooth indirect light to well within 1%.
TEST(Sensors, TheIntegratingRoomsMeanIrradianceOnAGrid) {
  const float rho = 0.5f;
  SceneBuilder b("cube");
  const uint32_t wall = b.addMaterial({"wall", Color(rho), Color(0.0f), false});
  test::addInwardCube(b, [&](int) { return wall; });
  b.scene().lights.push_back(test::pointLight(Vec3(0.5f), Color(1.0f)));
  const Scene scene = b.build();

  constexpr int n = 16;
  std::vector<SensorPoint> grid;
  double direct = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec3 p((float(i) + 0.5f) / n, 0.0f, (float(j) + 0.5f) / n);
      grid.push_back({p, Vec3(0, 1, 0)});
      const double r2 = std::pow(p.x - 0.5, 2) + std::pow(p.z - 0.5, 2);
      direct += 0.5 / std::pow(0.25 + r2, 1.5) / (n * n);
    }
  const double pi = glm::pi<double>();
  const double indirect = 4.0 * pi * rho / (6.0 * (1.0 - rho));
  const double expected = direct + indirect;
  auto mean = [](const std::vector<Color>& values) {
    double sum = 0.0;
    for (const Color& c : values) sum += c.g;
    return sum / double(values.size());
  };
  const PatchRadiosity patch(scene, test::uncachedPatchSettings(1200));
  const VoxelRadiosity voxel(scene, smallVoxelSettings());
  const std::string what = "integrating room, floor grid mean, ";
  EXPECT_LT(
      std::abs(reportedError(what + "patch", mean(solvedSensors(scene, patch, grid)), expected)),
      0.01);
  EXPECT_LT(
      std::abs(reportedError(what + "voxel", mean(solvedSensors(scene, voxel, grid)), expected)),
      0.03);
  EXPECT_LT(std::abs(reportedError(what + "path tracer", mean(tracedSensors(scene, grid, 1024)),
                                   expected)),
            0.01);
}

// 1e-5 W/mm^2 is 10 W/m^2, 1,790 lx at 179 lm/W; the figures of a set follow from its points.
TEST(Sensors, ReadingsInLuxWithTheirMeanAndUniformity) {
  const LengthUnit mm = *lengthUnitNamed("mm");
  EXPECT_NEAR(*illuminanceLux(Color(1e-5f), mm), 1790.0, 1e-6 * 1790.0);
  EXPECT_FALSE(illuminanceLux(Color(1.0f), LengthUnit{}).has_value());
  const SensorSet sets[] = {{"desk", {{Vec3(0.0f), Vec3(0, 1, 0)}}},
                            {"plane", {{Vec3(1.0f), Vec3(0, 1, 0)}, {Vec3(2.0f), Vec3(0, 1, 0)}}}};
  const Color irradiance[] = {Color(1.0f / 179.0f), Color(2.0f / 179.0f), Color(6.0f / 179.0f)};
  const std::vector<SensorReading> r = sensorReadings(sets, irradiance, *lengthUnitNamed("m"));
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[1].name, "plane");
  EXPECT_NEAR(r[1].meanLux, 4.0, 1e-5);
  EXPECT_NEAR(r[1].minLux, 2.0, 1e-5);
  EXPECT_NEAR(r[1].maxLux, 6.0, 1e-5);
  EXPECT_NEAR(r[1].uniformity, 0.5, 1e-6);
  EXPECT_TRUE(sensorReadings(sets, irradiance, LengthUnit{})[1].lux.empty());
}

}  // namespace
}  // namespace rad
