// The voxel method on the geometry real interiors have: round columns, arches, thin railings and
// a vault (the built-in atrium), and a column and small objects under a point light, against
// closed-form quadrature and the reference path tracer.
#include <gtest/gtest.h>
#include <radiosity/scene_builder.h>
#include <radiosity/scene_loader.h>
#include <radiosity/voxel_radiosity.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <numbers>

#include "render/test_scenes.h"
#include "voxel/voxel_test_scenes.h"

namespace rad {
namespace {

float luminance(const Color& c) {
  return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

constexpr int kFacets = 24;
constexpr float kRadius = 0.35f, kHeight = 4.0f;

// The corners of facet k of a vertical prism of kFacets sides around the y axis.
std::array<Vec3, 4> facet(int k) {
  const float a0 = 2.0f * std::numbers::pi_v<float> * float(k) / kFacets;
  const float a1 = 2.0f * std::numbers::pi_v<float> * float(k + 1) / kFacets;
  const Vec3 p0(kRadius * std::cos(a0), 0.0f, kRadius * std::sin(a0));
  const Vec3 p1(kRadius * std::cos(a1), 0.0f, kRadius * std::sin(a1));
  return {p0, p0 + Vec3(0, kHeight, 0), p1 + Vec3(0, kHeight, 0), p1};
}

TEST(VoxelRealInterior, ColumnGetsThePointLightsDirectLight) {
  // A black column of 24 facets alone under a point light: the irradiance is the direct light
  // only, I cos / d^2 wherever a facet faces the light (a convex solid does not shadow itself).
  // Its mean, by a 400 x 400 midpoint rule per facet here, is the reference. The first shot's
  // shadow rays left from the sides' centroids, which lie inside a curved solid (a chord below
  // the facets): 13% of the light was lost at 0.023 m voxels.
  const Vec3 lightAt(2.0f, 2.6f, 0.5f);
  const float intensity = 60.0f;
  SceneBuilder b("column");
  const uint32_t black = b.addMaterial({"black", Color(0.0f)});
  const uint32_t column = b.addObject("column");
  for (int k = 0; k < kFacets; ++k) {
    const std::array<Vec3, 4> c = facet(k);
    std::array<uint32_t, 4> ids{};
    for (int i = 0; i < 4; ++i) ids[i] = b.addVertex(c[i], "column");
    b.addPolygon(ids, black, column, "column");
  }
  Scene scene = b.build();
  Light light;
  light.position = lightAt;
  light.intensity = Color(intensity);
  scene.lights = {light};

  double sum = 0.0, area = 0.0;
  constexpr int kSteps = 400;
  for (int k = 0; k < kFacets; ++k) {
    const std::array<Vec3, 4> c = facet(k);
    const Vec3 across = c[3] - c[0], up = c[1] - c[0];
    const Vec3 n = glm::normalize(glm::cross(up, across));
    const double cellArea = double(glm::length(across)) * kHeight / (kSteps * kSteps);
    for (int i = 0; i < kSteps; ++i)
      for (int j = 0; j < kSteps; ++j) {
        const Vec3 p = c[0] + (float(i) + 0.5f) / kSteps * across + (float(j) + 0.5f) / kSteps * up;
        const Vec3 d = lightAt - p;
        const double cosine = glm::dot(n, glm::normalize(d));
        if (cosine > 0.0) sum += intensity * cosine / glm::dot(d, d) * cellArea;
      }
    area += double(glm::length(across)) * kHeight;
  }
  const double expected = sum / area;

  VoxelRadiositySettings settings;
  settings.targetVoxels = 40000;  // 0.025 m voxels, 14 across the column
  settings.sphereRadius = 4;
  settings.iterations = 1;
  const VoxelRadiosity solution(scene, settings);
  const std::vector<ObjectRadiometry> objects = solution.objectRadiometry();
  ASSERT_EQ(objects.size(), 1u);
  EXPECT_NEAR(objects[0].meanIrradiance.r, expected, 0.01 * expected);
}

// The mean over an object's triangles that face the light of I cos / d^2, by the midpoint rule
// on k^2 sub-triangles each: its exact direct irradiance from a point light when nothing casts a
// shadow on it.
double meanDirectIrradiance(const Scene& scene, uint32_t object, const Vec3& lightAt,
                            float intensity) {
  constexpr int k = 40;
  double sum = 0.0, area = 0.0;
  for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
    if (scene.faceOf(t).object != object) continue;
    const Vec3 a = scene.positions[scene.triangles[t][0]];
    const Vec3 ab = scene.positions[scene.triangles[t][1]] - a;
    const Vec3 ac = scene.positions[scene.triangles[t][2]] - a;
    const Vec3 n = scene.triangleNormal(t);
    const double piece = double(scene.triangleArea(t)) / (k * k);
    auto add = [&](float i, float j) {
      const Vec3 d = lightAt - (a + i / k * ab + j / k * ac);
      const double cosine = glm::dot(n, glm::normalize(d));
      if (cosine > 0.0) sum += intensity * cosine / glm::dot(d, d) * piece;
    };
    for (int i = 0; i < k; ++i)
      for (int j = 0; i + j < k; ++j) {
        add(float(i) + 1.0f / 3.0f, float(j) + 1.0f / 3.0f);
        if (i + j < k - 1) add(float(i) + 2.0f / 3.0f, float(j) + 2.0f / 3.0f);
      }
    area += scene.triangleArea(t);
  }
  return sum / area;
}

// A box of half sizes `half`, turned by `turn` about y, centred at c, its faces outward.
void addBox(SceneBuilder& b, const Vec3& c, const Vec3& half, float turn, uint32_t material,
            uint32_t object) {
  const glm::mat3 r(glm::rotate(glm::mat4(1.0f), turn, Vec3(0, 1, 0)));
  for (int axis = 0; axis < 3; ++axis)
    for (float sign : {-1.0f, 1.0f}) {
      std::array<Vec3, 4> q = test::axisSquare(Vec3(0.0f), axis, 2.0f);
      Vec3 out(0.0f);
      out[axis] = sign;
      for (Vec3& p : q) {
        p[axis] = sign;
        p = c + r * (p * half);
      }
      test::addQuadFacing(b, q, r * out, material, object);
    }
}

TEST(VoxelRealInterior, SmallObjectsGetThePointLightsDirectLight) {
  // A black sphere 2 to 3 voxels wide (a door knob), a rod and a block thinner than two voxels,
  // turned off the grid, under a point light, apart enough that none shades another: each
  // object's mean irradiance is its direct light, against meanDirectIrradiance within 1% at
  // three voxel sizes. Lit from each side's centroid along its mean normal, the sphere was
  // -1.3%, +2.7% and -1.6% (a side's facets fan out; on a real door knob, -17%).
  const Vec3 lightAt(0.4f, 1.5f, 0.7f);
  const float intensity = 10.0f;
  SceneBuilder b("small objects");
  const uint32_t black = b.addMaterial({"black", Color(0.0f)});
  const uint32_t knob = b.addObject("knob");
  test::addSphere(b, Vec3(0.013f, 0.004f, 0.021f), 0.03f, false, black, knob);
  const uint32_t rod = b.addObject("rod");
  addBox(b, Vec3(0.52f, 0.011f, 0.0f), Vec3(0.02f, 0.02f, 0.3f), 0.3f, black, rod);
  const uint32_t block = b.addObject("block");
  addBox(b, Vec3(1.03f, 0.017f, 0.04f), Vec3(0.01f, 0.015f, 0.012f), 0.6f, black, block);
  Scene scene = b.build();
  Light light;
  light.position = lightAt;
  light.intensity = Color(intensity);
  scene.lights = {light};
  const std::map<std::string, double> expected{
      {"knob", meanDirectIrradiance(scene, knob, lightAt, intensity)},
      {"rod", meanDirectIrradiance(scene, rod, lightAt, intensity)},
      {"block", meanDirectIrradiance(scene, block, lightAt, intensity)}};
  for (float voxel : {0.02f, 0.025f, 0.03f}) {
    VoxelRadiositySettings settings;
    settings.voxelSize = voxel;
    settings.sphereRadius = 4;
    settings.iterations = 1;
    const VoxelRadiosity solution(scene, settings);
    for (const ObjectRadiometry& o : solution.objectRadiometry()) {
      const double h = expected.at(o.name);
      EXPECT_NEAR(o.meanIrradiance.r, h, 0.01 * h) << o.name << " at voxels of " << voxel;
    }
  }
}

TEST(VoxelRealInterior, AtriumMatchesThePathTracerPerObject) {
  // Every object of the generated atrium (columns, arches, railings of 2 cm bars, a barrel vault,
  // galleries, under two point lights and a spot) within 5% of the path tracer's mean
  // irradiance, at settings that take seconds (800k voxels of 4.3 cm, R = 6). Measured with
  // atrium:1: -0.4..-3.6% (railings the farthest: bars thinner than a voxel shade the galleries as
  // if they were a voxel wide; 1.6M voxels: -0.4..-2.8%). Before the first shot left from the
  // surface and rays passed convex edges between voxels: columns -40%, railings -11% at 200k.
  const Scene scene = loadScene("atrium:1");
  const std::map<std::string, ObjectRadiometry> traced =
      test::tracedObjectMeans(scene, 20000, 4, 7);
  VoxelRadiositySettings settings;
  settings.targetVoxels = 800000;
  settings.sphereRadius = 6;
  const VoxelRadiosity solution(scene, settings);
  for (const ObjectRadiometry& o : solution.objectRadiometry()) {
    const float expected = luminance(traced.at(o.name).meanIrradiance);
    EXPECT_NEAR(luminance(o.meanIrradiance), expected, 0.05f * expected) << o.name;
  }
}

}  // namespace
}  // namespace rad
