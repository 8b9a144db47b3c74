// The methods' seam: a model prepared once per geometry (mesh or voxel grid), solved per light
// state.
#include <gtest/gtest.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/ray_caster.h>
#include <radiosity/scene_loader.h>
#include <radiosity/surface_radiance.h>
#include <radiosity/voxel_radiosity.h>

#include <filesystem>
#include <optional>

namespace rad {

namespace {

namespace fs = std::filesystem;

PatchRadiositySettings noDiskCache() {
  PatchRadiositySettings s;
  s.cacheDir.clear();
  return s;
}

void expectSameObjects(const PatchRadiosity& a, const PatchRadiosity& b) {
  const std::vector<ObjectRadiometry> x = a.objectRadiometry(), y = b.objectRadiometry();
  ASSERT_EQ(x.size(), y.size());
  for (size_t o = 0; o < x.size(); ++o) {
    EXPECT_EQ(x[o].meanIrradiance, y[o].meanIrradiance) << x[o].name;
    EXPECT_EQ(x[o].meanRadiosity, y[o].meanRadiosity) << x[o].name;
  }
}

// Solving a model under moved lights is solving the scene with those lights: the same numbers
// bit for bit, the base mesh and the ray caster made once.
TEST(PatchModel, SolveWithOtherLightsEqualsTheSceneWithThem) {
  const Scene scene = loadScene("cornell-spot");
  Scene moved = scene;
  moved.lights[0].position.x -= 120.0f;
  moved.lights[0].direction = glm::normalize(Vec3(0.3f, -1.0f, 0.1f));
  const RayCaster caster(scene);
  const PatchModel model(scene, caster, noDiskCache());
  const PatchRadiosity here = model.solve(moved.lights);
  const PatchRadiosity fromScratch(moved, noDiskCache());
  expectSameObjects(here, fromScratch);
  EXPECT_EQ(here.stats().patches, fromScratch.stats().patches);
  ASSERT_EQ(here.directLights().size(), 1u);
  EXPECT_EQ(here.directLights()[0].position, moved.lights[0].position);
}

// The master table by node: move a light, solve, move it back, solve. The second solve casts
// only the rows of the nodes its refinement made; the third casts none (its patches were all
// solved before) and gives the first answer again.
TEST(PatchModel, MasterTableCastsOnlyRowsNeverComputed) {
  const Scene scene = loadScene("cornell-spot");
  std::vector<Light> away = scene.lights;
  away[0].position.z += 150.0f;
  const PatchModel model(scene, noDiskCache());
  const PatchRadiosity first = model.solve(scene.lights);
  const PatchRadiosity second = model.solve(away);
  const PatchRadiosity third = model.solve(scene.lights);
  EXPECT_EQ(first.stats().rowsComputed, first.stats().patches);
  EXPECT_EQ(first.stats().rowsReused, 0u);
  EXPECT_NE(second.stats().patches, first.stats().patches);  // the beam moved: other patches
  EXPECT_GT(second.stats().rowsReused, second.stats().patches / 2);
  EXPECT_EQ(second.stats().rowsComputed + second.stats().rowsReused, second.stats().patches);
  EXPECT_EQ(third.stats().rowsComputed, 0u);
  EXPECT_EQ(third.stats().rowsReused, third.stats().patches);
  EXPECT_LT(third.stats().rays, first.stats().rays / 10);  // only the lights' shadow rays
  expectSameObjects(third, first);
}

// The disk cache holds the master table, keyed by the geometry and the base meshing, not the
// lights: a run with the light elsewhere reads the rows of an earlier run and casts only those
// of its new nodes, and its answer equals a solve without the cache.
TEST(PatchModel, CacheFromAnotherLightIsReused) {
  const fs::path dir = fs::path(::testing::TempDir()) / "radiosity_master_cache";
  fs::remove_all(dir);
  Scene scene = loadScene("cornell-spot");
  PatchRadiositySettings cached;
  cached.cacheDir = dir.string();
  const PatchRadiosity first(scene, cached);
  EXPECT_FALSE(first.stats().cacheLoaded);
  ASSERT_TRUE(fs::exists(first.stats().cacheFile)) << first.stats().cacheFile;
  scene.lights[0].position.x -= 130.0f;
  const PatchRadiosity moved(scene, cached);
  EXPECT_TRUE(moved.stats().cacheLoaded);
  EXPECT_TRUE(moved.stats().warnings.empty());
  EXPECT_GT(moved.stats().rowsReused, moved.stats().patches / 2);
  EXPECT_LT(moved.stats().rowsComputed, moved.stats().patches / 2);
  expectSameObjects(moved, PatchRadiosity(scene, noDiskCache()));
}

// A solution outlives the model it came from, and its picture takes the direct light of the
// lights it was solved with, not the scene's.
TEST(PatchModel, SolutionKeepsItsModelAndItsLights) {
  const Scene scene = loadScene("cornell-spot");
  Scene moved = scene;
  moved.lights[0].position.x += 100.0f;
  std::optional<PatchRadiosity> solution;
  {
    const PatchModel model(scene, noDiskCache());
    solution.emplace(model.solve(moved.lights));
  }
  const PatchRadiosity reference(moved, noDiskCache());
  Camera camera = scene.cameraOrDefault();
  camera.width = camera.height = 24;
  SurfaceRenderSettings render;
  render.samplesPerPixel = 1;
  const Image a = renderSurfaceRadiance(scene, camera, *solution, render);
  const Image b = renderSurfaceRadiance(moved, camera, reference, render);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) EXPECT_EQ(a.at(x, y), b.at(x, y)) << x << ", " << y;
}

// The voxel grid made once serves any lights: a moved spot's solution equals voxelizing and
// solving the scene with it, bit for bit (the first shot is deterministic).
TEST(VoxelModel, SolveWithOtherLightsEqualsTheSceneWithThem) {
  const Scene scene = loadScene("cornell-spot");
  Scene moved = scene;
  moved.lights[0].position.z -= 100.0f;
  VoxelRadiositySettings s;
  s.targetVoxels = 5000;
  s.sphereRadius = 4;
  s.iterations = 2;
  s.directSamples = 4;
  const RayCaster caster(scene);
  const VoxelModel model(scene, caster, s);
  const VoxelRadiosity here = model.solve(moved.lights), fromScratch(moved, s);
  const std::vector<ObjectRadiometry> x = here.objectRadiometry(),
                                      y = fromScratch.objectRadiometry();
  ASSERT_EQ(x.size(), y.size());
  for (size_t o = 0; o < x.size(); ++o)
    EXPECT_EQ(x[o].meanRadiosity, y[o].meanRadiosity) << x[o].name;
  const VoxelRadiosity original = model.solve(scene.lights);
  EXPECT_NE(original.objectRadiometry()[0].meanRadiosity, x[0].meanRadiosity);  // the floor
  ASSERT_EQ(here.directLights().size(), 1u);
  EXPECT_EQ(here.directLights()[0].position, moved.lights[0].position);
}

}  // namespace
}  // namespace rad
