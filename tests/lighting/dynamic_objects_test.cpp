// Dynamic objects: placed where their paths say, and lit at their vertices by probes of the
// static solution (against a furnace's closed form and the colour of the wall a vertex faces).
#include "lighting/dynamic_objects.h"

#include <gtest/gtest.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/scene_builder.h>
#include <radiosity/scene_loader.h>
#include <radiosity/voxel_radiosity.h>

#include <glm/gtc/constants.hpp>

#include "render/test_scenes.h"

namespace rad {
namespace {

// A cube of side `size` centred on its own origin, faces outward, rho 0.5.
std::shared_ptr<const Scene> cubeMesh(float size) {
  SceneBuilder b("cube");
  const uint32_t m = b.addMaterial({"grey", Color(0.5f), Color(0.0f), false});
  const uint32_t o = b.addObject("cube");
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      Vec3 centre(0.0f), out(0.0f);
      centre[axis] = out[axis] = side == 0 ? -0.5f * size : 0.5f * size;
      test::addQuadFacing(b, test::axisSquare(centre, axis, size), glm::normalize(out), m, o);
    }
  return std::make_shared<const Scene>(b.build());
}

TEST(DynamicObjects, PlacedWhereTheirPathSays) {
  Scene scene = loadScene("cornell");
  DynamicObject ball{"ball", cubeMesh(10.0f), std::nullopt, {}};
  ball.path = {{0.0, Vec3(100, 100, 100), Vec3(0.0f)}, {2.0, Vec3(300, 100, 100), Vec3(0, 90, 0)}};
  scene.dynamicObjects.push_back(ball);
  const Scene placed = scene.withDynamicObjectsAt(1.0);
  EXPECT_EQ(placed.staticTriangles, scene.triangles.size());
  EXPECT_EQ(placed.triangles.size(), scene.triangles.size() + 12);
  EXPECT_TRUE(placed.dynamicObjects.empty());
  // Halfway: at x = 200, turned 45 degrees about y (a corner of the cube swung round).
  Vec3 centre(0.0f);
  for (size_t v = scene.positions.size(); v < placed.positions.size(); ++v)
    centre += placed.positions[v] / float(placed.positions.size() - scene.positions.size());
  EXPECT_NEAR(centre.x, 200.0f, 1e-3f);
  const glm::mat4 m = ball.placementAt(1.0);
  const Vec3 corner = Vec3(m * glm::vec4(5.0f, 0.0f, 5.0f, 1.0f)) - Vec3(200, 100, 100);
  EXPECT_NEAR(corner.x, 5.0f * std::sqrt(2.0f), 1e-3f);  // rotated onto the x axis
  EXPECT_NEAR(corner.z, 0.0f, 1e-3f);
  // The own triangles keep their places and materials.
  EXPECT_EQ(placed.materialOf(0).name, scene.materialOf(0).name);
}

// A furnace: the object inside a closed box whose walls emit L (rho 0); every vertex's
// irradiance is pi L (each way within 1%, here the default: harmonics).
// The unit cube seen from inside, its walls emitting `l` (rho 0), solved; then a cube of side 0.2
// (rho 0.5) placed at its centre as a dynamic object.
struct Furnace {
  explicit Furnace(const Color& l) : scene(walls(l)), solution(scene, settings()) {
    scene.dynamicObjects.push_back(
        {"cube", cubeMesh(0.2f), std::nullopt, {{0.0, Vec3(0.5f), std::nullopt}}});
  }
  static Scene walls(const Color& l) {
    SceneBuilder b("furnace");
    const uint32_t glow = b.addMaterial({"glow", Color(0.0f), l, false});
    test::addInwardCube(b, [&](int) { return glow; });
    return b.build();
  }
  static PatchRadiositySettings settings() {
    PatchRadiositySettings s;
    s.targetPatches = 200;
    return s;
  }
  Scene scene;
  PatchRadiosity solution;
};

TEST(DynamicObjects, FurnaceVerticesGetPiL) {
  const Color l(1.0f, 0.5f, 0.25f);
  Furnace furnace(l);
  const Scene& scene = furnace.scene;
  const PatchRadiosity& solution = furnace.solution;
  const Scene placed = scene.withDynamicObjectsAt(0.0);
  const RayCaster staticCaster(scene), placedCaster(placed);
  const DynamicObjectLighting lighting(placed, solution, staticCaster, placedCaster);
  for (uint32_t v = uint32_t(scene.positions.size()); v < placed.positions.size(); ++v)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(lighting.vertexIrradiance(v)[c], glm::pi<float>() * l[c],
                  0.01f * glm::pi<float>() * l[c]);
}

// In the Cornell box a vertex facing the red wall gets more red than green, one facing the green
// wall the other way round.
TEST(DynamicObjects, AVertexFacingTheRedWallGetsMoreRed) {
  Scene scene = loadScene("cornell");
  PatchRadiositySettings settings;
  settings.targetPatches = 1000;
  const PatchRadiosity solution(scene, settings);
  scene.dynamicObjects.push_back(
      {"cube", cubeMesh(40.0f), std::nullopt, {{0.0, Vec3(278, 274, 280), std::nullopt}}});
  const Scene placed = scene.withDynamicObjectsAt(0.0);
  const RayCaster staticCaster(scene), placedCaster(placed);
  const DynamicObjectLighting lighting(placed, solution, staticCaster, placedCaster);
  // The red wall is at x = 550 or so, the green one at x = 0: the cube's +x and -x faces.
  Color towardRed(0.0f), towardGreen(0.0f);
  for (uint32_t t = placed.staticTriangles; t < placed.triangles.size(); ++t) {
    const Vec3 n = placed.triangleNormal(t);
    for (int k = 0; k < 3; ++k) {
      const Color e = lighting.vertexIrradiance(placed.triangles[t][k]);
      if (n.x > 0.9f) towardRed += e;
      if (n.x < -0.9f) towardGreen += e;
    }
  }
  EXPECT_GT(towardRed.r / towardRed.g, towardGreen.r / towardGreen.g);
  EXPECT_GT(towardGreen.g / towardGreen.r, towardRed.g / towardRed.r);
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

// The light an object reflects, summarized at its centre: a cube of radiosity B on every face
// sends B A / pi along each axis (one face's projected area) and B times its area in all.
TEST(DynamicObjects, ObjectLightCarriesWhatTheObjectReflects) {
  Furnace furnace(Color(1.0f));
  const Scene placed = furnace.scene.withDynamicObjectsAt(0.0);
  const RayCaster caster(furnace.scene), placedCaster(placed);
  const std::vector<Light> lights =
      DynamicObjectLighting(placed, furnace.solution, caster, placedCaster).objectLights();
  ASSERT_EQ(lights.size(), 1u);
  const float b0 = 0.5f * glm::pi<float>();  // rho 0.5 times pi L
  const float face = 0.2f * 0.2f;
  EXPECT_NEAR(lights[0].intensityToward(Vec3(1, 0, 0)).r, b0 * face / glm::pi<float>(), 2e-3f);
  EXPECT_NEAR(lights[0].power().g, b0 * 6.0f * face, 0.01f * b0 * 6.0f * face);
  EXPECT_NEAR(glm::length(lights[0].position - Vec3(0.5f)), 0.0f, 1e-5f);
}

}  // namespace
}  // namespace rad

#include "lighting/light_test_scenes.h"

namespace rad {
namespace {

// The floor [-1, 1]^2 under a point light 2 above its centre, a cube of side 0.5 hung at height 1
// between them (its shadow: within 0.4 of the centre fully, out to 0.67 in part).
Scene floorWithHungCube() {
  Scene scene = test::floorUnderLight(1.0f, test::pointLight(Vec3(0, 2, 0), Color(1.0f)));
  scene.dynamicObjects.push_back(
      {"cube", cubeMesh(0.5f), std::nullopt, {{0.0, Vec3(0, 1, 0), std::nullopt}}});
  return scene;
}

// A cube hung under a point light shadows the floor in the static solution when the solve is
// given the scene with the cube placed: the patches under it get none of the light's direct
// light, those far from it all of it.
TEST(DynamicObjects, ShadowTheLightsDirectLightInTheStaticSolution) {
  const Scene scene = floorWithHungCube();
  PatchRadiositySettings settings;
  settings.targetPatches = 400;
  settings.refineLevels = 0;
  const PatchModel model(scene, settings);
  const Scene placed = scene.withDynamicObjectsAt(0.0);
  const RayCaster placedCaster(placed);
  const PatchRadiosity open = model.solve(scene.lights);
  const PatchRadiosity shadowed = model.solve(scene.lights, placedCaster);
  size_t under = 0, far = 0;
  for (size_t p = 0; p < open.elementCount(); ++p) {
    const SurfaceElement e = shadowed.element(p);
    const float r = std::max(std::abs(e.position.x), std::abs(e.position.z));
    if (r < 0.25f) {
      EXPECT_LT(e.irradiance.r, 1e-6f) << p;
      ++under;
    } else if (r > 0.75f) {
      EXPECT_FLOAT_EQ(e.irradiance.r, open.element(p).irradiance.r) << p;
      ++far;
    }
  }
  EXPECT_GT(under, 4u);
  EXPECT_GT(far, 50u);
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

// Selective update: a probe is captured again only when its object moved more than the
// threshold, or when the caller says the light changed.
TEST(DynamicObjects, ProbesAreCapturedAgainOnlyWhenNeeded) {
  Furnace furnace(Color(1.0f));
  const RayCaster caster(furnace.scene);
  ProbeCache cache;
  DynamicObjectSettings settings;
  settings.probeMoveThreshold = 0.1f;
  auto lightAt = [&](const Vec3& position) {
    furnace.scene.dynamicObjects[0].path = {{0.0, position, std::nullopt}};
    const Scene placed = furnace.scene.withDynamicObjectsAt(0.0);
    const RayCaster placedCaster(placed);
    const DynamicObjectLighting lighting(placed, furnace.solution, caster, placedCaster, settings,
                                         &cache);
    return cache.captures();
  };
  EXPECT_EQ(lightAt(Vec3(0.5f)), 1u);
  EXPECT_EQ(lightAt(Vec3(0.5f)), 1u);               // still
  EXPECT_EQ(lightAt(Vec3(0.55f, 0.5f, 0.5f)), 1u);  // moved 0.05: within the threshold
  EXPECT_EQ(lightAt(Vec3(0.7f, 0.5f, 0.5f)), 2u);   // moved 0.2
  cache.invalidate();                               // the lights changed
  EXPECT_EQ(lightAt(Vec3(0.7f, 0.5f, 0.5f)), 3u);
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

// The voxel method's first shot is shadowed the same way.
TEST(DynamicObjects, ShadowTheVoxelFirstShot) {
  const Scene scene = floorWithHungCube();
  VoxelRadiositySettings settings;
  settings.targetVoxels = 3000;
  settings.sphereRadius = 4;
  settings.iterations = 1;
  const VoxelModel model(scene, settings);
  const Scene placed = scene.withDynamicObjectsAt(0.0);
  const RayCaster placedCaster(placed);
  const VoxelRadiosity open = model.solve(scene.lights);
  const VoxelRadiosity shadowed = model.solve(scene.lights, placedCaster);
  size_t under = 0;
  for (size_t e = 0; e < open.elementCount(); ++e) {
    const SurfaceElement s = shadowed.element(e);
    if (std::max(std::abs(s.position.x), std::abs(s.position.z)) < 0.25f) {
      EXPECT_LT(s.irradiance.r, 1e-6f);
      EXPECT_GT(open.element(e).irradiance.r, 0.1f);
      ++under;
    }
  }
  EXPECT_GT(under, 4u);
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

// A bar across the Cornell box from the green wall to the red one: one probe at its middle gives
// both ends the middle's light; a grid of probes (100 apart) gives the end by the red wall more
// red against the end by the green wall, as the walls' bounce light does there.
TEST(DynamicObjects, ALargeObjectGetsSeveralProbes) {
  Scene scene = loadScene("cornell");
  SceneBuilder b("bar");
  const uint32_t m = b.addMaterial({"grey", Color(0.5f), Color(0.0f), false});
  const uint32_t o = b.addObject("bar");
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const Vec3 half(220.0f, 20.0f, 20.0f);
      Vec3 centre(0.0f), out(0.0f);
      centre[axis] = side == 0 ? -half[axis] : half[axis];
      out[axis] = side == 0 ? -1.0f : 1.0f;
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      std::array<Vec3, 4> q;
      const float su[4] = {-1, 1, 1, -1}, sv[4] = {-1, -1, 1, 1};
      for (int k = 0; k < 4; ++k) {
        q[k] = centre;
        q[k][u] += su[k] * half[u];
        q[k][v] += sv[k] * half[v];
      }
      test::addQuadFacing(b, q, out, m, o);
    }
  scene.dynamicObjects.push_back({"bar",
                                  std::make_shared<const Scene>(b.build()),
                                  std::nullopt,
                                  {{0.0, Vec3(278, 150, 280), std::nullopt}}});
  PatchRadiositySettings settings;
  settings.targetPatches = 1000;
  const PatchRadiosity solution(scene, settings);
  const Scene placed = scene.withDynamicObjectsAt(0.0);
  const RayCaster staticCaster(scene), placedCaster(placed);
  // Red over green of the bar's upward face near each end.
  auto redness = [&](const DynamicObjectLighting& lighting, float x) {
    Color sum(0.0f);
    for (uint32_t v = uint32_t(scene.positions.size()); v < placed.positions.size(); ++v)
      if (std::abs(placed.positions[v].x - x) < 1.0f) sum += lighting.vertexIrradiance(v);
    return sum.r / sum.g;
  };
  DynamicObjectSettings grid;
  grid.probeSpacing = 100.0f;
  const DynamicObjectLighting one(placed, solution, staticCaster, placedCaster);
  const DynamicObjectLighting several(placed, solution, staticCaster, placedCaster, grid);
  // The red wall is at x = 550 or so: the bar's +x end at 498, its -x end at 58. (Even one
  // probe tells the ends apart a little: their corner normals lean toward their walls.)
  const float contrastOne = redness(one, 498.0f) / redness(one, 58.0f);
  const float contrastSeveral = redness(several, 498.0f) / redness(several, 58.0f);
  EXPECT_GT(contrastSeveral, 2.0f * contrastOne);  // measured: 1.14 with one probe, 3.10 with 5
}

}  // namespace
}  // namespace rad
