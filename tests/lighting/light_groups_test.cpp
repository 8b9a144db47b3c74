// Light groups: radiosity is linear in the emitted light, so a combination of the groups'
// solutions, each solved alone, must be the solve of the scene with its emitters scaled the same
// way (within the solvers' tolerance), for the patch and the voxel methods alike.
#include <gtest/gtest.h>
#include <radiosity/error.h>
#include <radiosity/light_groups.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/scene_loader.h>
#include <radiosity/voxel_radiosity.h>

#include "lighting/light_test_scenes.h"

namespace rad {
namespace {

// The Cornell box (its ceiling lamp, material "light") with a desk lamp (point light, group
// "desk") and a spot of no group ("light1").
Scene boxWithLamps() {
  Scene scene = loadScene("cornell");
  Light desk = test::pointLight(Vec3(150.0f, 300.0f, 200.0f), Color(2e4f, 1.8e4f, 1.5e4f));
  desk.group = "desk";
  scene.lights.push_back(desk);
  scene.lights.push_back(
      test::downSpot(Vec3(400.0f, 500.0f, 300.0f), Color(8e4f, 8e4f, 9e4f), 20.0f, 35.0f));
  return scene;
}

// Scales that dim and tint. (Not 0: an emitter switched off in the scene itself would no longer
// count as one, and the hemisphere estimator computes emitters' columns exactly, so the
// reference's form factors would differ.)
const std::vector<GroupScale> kScales = {
    {"light", Color(0.1f)}, {"desk", Color(0.25f)}, {"light1", Color(1.0f, 0.5f, 0.2f)}};

TEST(LightGroups, LightsByGroupOrOwnAndMaterialsByName) {
  const Scene scene = boxWithLamps();
  const std::vector<LightGroup> groups = lightGroupsOf(scene, scene.lights);
  ASSERT_EQ(groups.size(), 3u);
  EXPECT_EQ(groups[0].name, "desk");
  EXPECT_EQ(groups[0].lights, std::vector<uint32_t>{0});
  EXPECT_EQ(groups[1].name, "light1");
  EXPECT_EQ(groups[1].lights, std::vector<uint32_t>{1});
  EXPECT_EQ(groups[2].name, "light");  // the emitting material
  EXPECT_TRUE(groups[2].lights.empty());
  ASSERT_EQ(groups[2].materials.size(), 1u);
  EXPECT_EQ(scene.materials[groups[2].materials[0]].name, "light");

  // A light naming the material's group joins it.
  Scene joined = scene;
  joined.lights[0].group = "light";
  const std::vector<LightGroup> two = lightGroupsOf(joined, joined.lights);
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(two[0].name, "light");
  EXPECT_EQ(two[0].lights, std::vector<uint32_t>{0});
  EXPECT_EQ(two[0].materials.size(), 1u);

  // A light without a group whose own name another light takes: refused, not merged.
  Scene clash = scene;
  clash.lights[0].group = "light1";
  EXPECT_THROW(lightGroupsOf(clash, clash.lights), InputError);
}

TEST(LightGroups, ScalesParseOneOrThreeNumbersAndRefuseTheRest) {
  EXPECT_EQ(parseGroupScale("desk=0.5").scale, Color(0.5f));
  const GroupScale tint = parseGroupScale("desk=1,0.5,0");
  EXPECT_EQ(tint.name, "desk");
  EXPECT_EQ(tint.scale, Color(1.0f, 0.5f, 0.0f));
  for (const char* bad : {"desk", "=1", "desk=", "desk=x", "desk=-1", "desk=1,2", "desk=inf",
                          "desk=1,2,3,4", "desk=1;"})
    EXPECT_THROW(parseGroupScale(bad), InputError) << bad;
  const Scene scene = boxWithLamps();
  const std::vector<LightGroup> groups = lightGroupsOf(scene, scene.lights);
  const std::vector<Color> scales = groupScalesFor(groups, kScales);
  EXPECT_EQ(scales[0], Color(0.25f));
  EXPECT_EQ(scales[2], Color(0.1f));
  try {
    groupScalesFor(groups, std::vector<GroupScale>{{"lamp", Color(1.0f)}});
    FAIL() << "an unknown group was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("desk, light1, light"), std::string::npos) << e.what();
  }
}

// The scene with its emitters scaled as kScales asks: the reference a combination must equal.
Scene scaledScene(const Scene& scene) {
  Scene scaled = scene;
  const std::vector<LightGroup> groups = lightGroupsOf(scene, scene.lights);
  scaleEmitters(scaled, groups, groupScalesFor(groups, kScales));
  return scaled;
}

// Tight solves (tolerance 1e-6), so that the bound below is the combination's, not the solver's.
// The mesh is not refined for the lights: a light switched off refines nothing, so the scaled
// scene would mesh differently.
PatchRadiositySettings patchSettings() {
  PatchRadiositySettings s;
  s.targetPatches = 800;
  s.formFactorRays = 128;
  s.tolerance = 1e-6;
  s.refineLevels = 0;
  return s;
}

TEST(LightGroups, PatchCombinationEqualsASolveWithTheEmittersScaled) {
  const Scene scene = boxWithLamps();
  PatchRadiositySettings apart = patchSettings();
  apart.lightGroups = true;
  PatchRadiosity grouped(scene, apart);
  ASSERT_EQ(grouped.lightGroups().size(), 3u);
  // At scale 1 the groups add up to the scene as it is.
  const PatchRadiosity whole(scene, patchSettings());
  EXPECT_LE(largestRadiosityDifference(grouped, whole), 1e-4);

  grouped.setGroupScales(groupScalesFor(grouped.lightGroups(), kScales));
  const Scene scaled = scaledScene(scene);
  const PatchRadiosity reference(scaled, patchSettings());
  EXPECT_LE(largestRadiosityDifference(grouped, reference), 1e-4);
  // What the renderer sees agrees too: the lamp's emission and the lights scaled.
  const uint32_t lamp = grouped.lightGroups()[2].materials[0];
  EXPECT_EQ(grouped.emissionScales()[lamp], Color(0.1f));
  EXPECT_EQ(grouped.directLights()[0].intensity, scaled.lights[0].intensity);

  // Switched off: the lamp emits nothing, and each object's shares (summing to one) give it none.
  grouped.setGroupScales(std::vector<Color>{Color(1.0f), Color(1.0f), Color(0.0f)});
  for (size_t p = 0; p < grouped.elementCount(); ++p)
    EXPECT_EQ(grouped.element(p).emitted, Color(0.0f));
  for (const ObjectRadiometry& o : grouped.objectRadiometry()) {
    ASSERT_EQ(o.groupShares.size(), 3u);
    EXPECT_NEAR(o.groupShares[0] + o.groupShares[1] + o.groupShares[2], 1.0, 1e-9) << o.name;
    EXPECT_EQ(o.groupShares[2], 0.0) << o.name;
  }
  EXPECT_THROW(grouped.setGroupScales(std::vector<Color>(2, Color(1.0f))), std::invalid_argument);
}

// With the mesh refined for the lights: one mesh, refined for all of them, whatever the scales.
TEST(LightGroups, PatchGroupsShareTheMeshRefinedForAllTheLights) {
  const Scene scene = boxWithLamps();
  PatchRadiositySettings refined = patchSettings();
  refined.refineLevels = 2;
  const PatchRadiosity whole(scene, refined);
  refined.lightGroups = true;
  PatchRadiosity grouped(scene, refined);
  ASSERT_EQ(grouped.elementCount(), whole.elementCount());
  EXPECT_GT(grouped.stats().refinedSplits, 0u);
  EXPECT_LE(largestRadiosityDifference(grouped, whole), 1e-4);
}

// The voxel method's sweeps are linear in what they send and draw the same lines for every
// group (one seed), so its groups add up as closely as its half-float packing allows (measured:
// 0.04% of the mean radiosity at scale 1, 0.08% scaled; bound 0.2%). No tail
// estimate: it extrapolates each solve's own bounce ratio, which is not linear.
VoxelRadiositySettings voxelSettings() {
  VoxelRadiositySettings s;
  s.targetVoxels = 6000;
  s.sphereRadius = 8;
  s.iterations = 4;
  s.directSamples = 16;
  s.estimateTail = false;
  return s;
}

TEST(LightGroups, VoxelCombinationEqualsASolveWithTheEmittersScaled) {
  const Scene scene = boxWithLamps();
  VoxelRadiositySettings apart = voxelSettings();
  apart.lightGroups = true;
  VoxelRadiosity grouped(scene, apart);
  ASSERT_EQ(grouped.lightGroups().size(), 3u);
  const VoxelRadiosity whole(scene, voxelSettings());
  EXPECT_LE(largestRadiosityDifference(grouped, whole), 0.002);

  grouped.setGroupScales(groupScalesFor(grouped.lightGroups(), kScales));
  const VoxelRadiosity reference(scaledScene(scene), voxelSettings());
  EXPECT_LE(largestRadiosityDifference(grouped, reference), 0.002);
  for (const ObjectRadiometry& o : grouped.objectRadiometry()) {
    if (o.area > 0.0) {
      EXPECT_NEAR(o.groupShares[0] + o.groupShares[1] + o.groupShares[2], 1.0, 1e-9) << o.name;
    }
  }
}

}  // namespace
}  // namespace rad
