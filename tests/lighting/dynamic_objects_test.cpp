// Dynamic objects: placed where their paths say, and lit at their vertices by probes of the
// static solution (against a furnace's closed form and the colour of the wall a vertex faces).
#include "probes/dynamic_objects.h"

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
  // A light per lobe, each from the middle of the face that sends it.
  ASSERT_EQ(lights.size(), 6u);
  const float b0 = 0.5f * glm::pi<float>();  // rho 0.5 times pi L
  const float face = 0.2f * 0.2f;
  float power = 0.0f;
  for (const Light& l : lights) {
    power += l.power().g;
    EXPECT_EQ(l.group, "object:cube");
  }
  EXPECT_NEAR(power, b0 * 6.0f * face, 0.01f * b0 * 6.0f * face);
  EXPECT_NEAR(lights[0].intensityToward(Vec3(1, 0, 0)).r, b0 * face / glm::pi<float>(), 2e-3f);
  EXPECT_EQ(lights[0].intensityToward(Vec3(-1, 0, 0)).r, 0.0f);
  EXPECT_NEAR(glm::distance(lights[0].position, Vec3(0.6f, 0.5f, 0.5f)), 0.0f, 1e-5f);
  EXPECT_NEAR(lights[0].radius, 0.1f * std::sqrt(3.0f) + 0.1f, 1e-5f);
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

namespace rad {
namespace {

// A cube of side `size` centred on its own origin, faces outward, each an n x n grid of quads
// (so that the light across a face is sampled at its vertices, not only at its corners).
std::shared_ptr<const Scene> gridCubeMesh(float size, int n, const Color& rho) {
  SceneBuilder b("grid cube");
  const uint32_t m = b.addMaterial({"white", rho, Color(0.0f), false});
  const uint32_t o = b.addObject("cube");
  const float cell = size / float(n);
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      Vec3 centre(0.0f), out(0.0f);
      centre[axis] = out[axis] = side == 0 ? -0.5f * size : 0.5f * size;
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          Vec3 c = centre;
          c[u] = -0.5f * size + (float(i) + 0.5f) * cell;
          c[v] = -0.5f * size + (float(j) + 0.5f) * cell;
          test::addQuadFacing(b, test::axisSquare(c, axis, cell), glm::normalize(out), m, o);
        }
    }
  return std::make_shared<const Scene>(b.build());
}

// The check of the light a dynamic object throws back: a 2 x 2 m wall (rho 0.5) with a
// spot just in front of it aimed away from it, at a white cube (rho 0.9, side 0.3) whose face
// toward the wall the beam covers. The wall gets no light but the cube's, so its radiosity rises
// by what the cube reflects; the patch method (the cube's light as six axis lobes at its centre,
// bounced once more) must match the path tracer with the cube in the scene within 10%.
TEST(DynamicObjects, AWhiteObjectBesideAWallRaisesItAsThePathTracerSays) {
  SceneBuilder b("wall");
  const uint32_t grey = b.addMaterial({"grey", Color(0.5f), Color(0.0f), false});
  test::addQuadFacing(b, test::axisSquare(Vec3(0.0f), 2, 2.0f), Vec3(0, 0, 1), grey,
                      b.addObject("wall"));
  Scene scene = b.build();
  Light spot;
  spot.type = LightType::Spot;
  spot.position = Vec3(0.0f, 0.0f, 0.15f);
  spot.direction = Vec3(0.0f, 0.0f, 1.0f);
  spot.intensity = Color(1.0f);
  spot.innerAngleDeg = 55.0f;  // the face's corners are 35 degrees off the axis
  spot.outerAngleDeg = 60.0f;
  scene.lights = {spot};
  scene.dynamicObjects.push_back({"cube",
                                  gridCubeMesh(0.3f, 10, Color(0.9f)),
                                  std::nullopt,
                                  {{0.0, Vec3(0.0f, 0.0f, 0.6f), std::nullopt}}});

  PatchRadiositySettings settings;
  settings.targetPatches = 1600;
  settings.refineLevels = 0;
  const RayCaster caster(scene);
  const PatchModel model(scene, caster, settings);
  const PatchRadiosity alone = model.solve(scene.lights);
  const Scene placed = scene.withDynamicObjectsAt(0.0);
  const RayCaster placedCaster(placed);
  std::vector<Light> lights = scene.lights;
  for (const Light& l : DynamicObjectLighting(placed, alone, caster, placedCaster).objectLights())
    lights.push_back(l);
  const PatchRadiosity withCube = model.solve(lights, placedCaster);
  const float before = luminance(alone.objectRadiometry()[0].meanRadiosity);
  const float after = luminance(withCube.objectRadiometry()[0].meanRadiosity);
  EXPECT_EQ(before, 0.0f);  // the spot shines away from the wall

  const std::map<std::string, ObjectRadiometry> traced =
      test::tracedObjectMeans(placed, 40000, 16, 5);
  const float expected = luminance(traced.at("wall").meanRadiosity);
  std::printf("wall radiosity from the cube: %.5f, path tracer %.5f (%+.1f%%)\n", after, expected,
              100.0 * (after / expected - 1.0));
  EXPECT_NEAR(after, expected, 0.1f * expected);

  // The voxel method the same way: its first shot takes the cube's lights.
  VoxelRadiositySettings voxelSettings;
  voxelSettings.targetVoxels = 20000;
  voxelSettings.sphereRadius = 6;
  const VoxelModel voxels(scene, caster, voxelSettings);
  const VoxelRadiosity voxelAlone = voxels.solve(scene.lights);
  std::vector<Light> voxelLights = scene.lights;
  for (const Light& l :
       DynamicObjectLighting(placed, voxelAlone, caster, placedCaster).objectLights())
    voxelLights.push_back(l);
  const float voxelAfter =
      luminance(voxels.solve(voxelLights, placedCaster).objectRadiometry()[0].meanRadiosity);
  std::printf("voxel: %.5f (%+.1f%%)\n", voxelAfter, 100.0 * (voxelAfter / expected - 1.0));
  EXPECT_NEAR(voxelAfter, expected, 0.1f * expected);
}

}  // namespace
}  // namespace rad
