// Relighting: a solution brought to moved lights by shooting the change must be the solution a
// fresh solve of those lights gives, after any sequence of moves, without drifting.
#include <gtest/gtest.h>
#include <radiosity/error.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/relighter.h>
#include <radiosity/scene_loader.h>

#include <cmath>
#include <glm/gtc/constants.hpp>

namespace rad {
namespace {

// The Cornell box's spot turned `degrees` about the z axis and moved `dx` along x.
std::vector<Light> swung(const Scene& scene, float degrees, float dx) {
  std::vector<Light> lights = scene.lights;
  const float a = glm::radians(degrees);
  lights[0].direction = Vec3(std::sin(a), -std::cos(a), 0.0f);
  lights[0].position.x += dx;
  return lights;
}

// A small model whose fresh solves converge far below the 0.5% asked of relighting (tolerance
// 1e-6), so that they are the reference, not a second approximate answer. The 0.5% per patch,
// relative to the mean radiosity, is the bound.
PatchRadiositySettings smallSettings() {
  PatchRadiositySettings s;
  s.targetPatches = 1500;
  s.formFactorRays = 128;
  s.tolerance = 1e-6;
  return s;
}

TEST(Relighter, TwentyMovesOfASpotMatchFreshSolvesAndComeBackWithoutNewRows) {
  const Scene scene = loadScene("cornell-spot");
  const PatchModel model(scene, smallSettings());
  Relighter relighter(model, scene.lights);
  std::vector<std::pair<float, float>> moves;  // (degrees, dx): out and back again
  for (int k = 1; k <= 10; ++k) moves.emplace_back(3.0f * k, 8.0f * k);
  for (int k = 9; k >= 0; --k) moves.emplace_back(3.0f * k, 8.0f * k);
  size_t meshChanges = 0, rowsOut = 0, rowsBack = 0;
  for (size_t i = 0; i < moves.size(); ++i) {
    const std::vector<Light> lights = swung(scene, moves[i].first, moves[i].second);
    const RelightStats& stats = relighter.relight(lights);
    meshChanges += stats.meshChanged;
    (i < 10 ? rowsOut : rowsBack) += stats.rowsComputed;
    const PatchRadiosity fresh = model.solve(lights);
    EXPECT_LE(largestRadiosityDifference(relighter.solution(), fresh), 0.005) << "move " << i;
  }
  EXPECT_GE(meshChanges, 10u);  // the beam's edge moved across patches
  EXPECT_GT(rowsOut, 0u);
  EXPECT_EQ(rowsBack, 0u);
}

// Two hundred small steps, each below the threshold for most patches: the skipped changes add up
// and are applied (re-anchored) before they matter, so the error stays as small as one move's.
// (A threshold of 1e-3 of the brightest patch; the default, 1e-4, skips less.)
TEST(Relighter, HundredsOfSmallStepsDoNotDrift) {
  const Scene scene = loadScene("cornell-spot");
  PatchRadiositySettings s = smallSettings();
  s.refineLevels = 0;  // the quadtree stays, so every change goes through the threshold
  const PatchModel model(scene, s);
  // Shooting, not the transfer a mesh this small would get by default.
  Relighter relighter(model, scene.lights, {.threshold = 1e-3, .transferPatches = 0});
  size_t skipped = 0, reanchored = 0;
  for (int k = 1; k <= 200; ++k) {
    const RelightStats& stats = relighter.relight(swung(scene, 0.05f * float(k), 0.0f));
    skipped += stats.patchesSkipped;
    reanchored += stats.reanchored;
  }
  EXPECT_GT(skipped, 0u);
  EXPECT_GT(reanchored, 0u);
  EXPECT_LE(
      largestRadiosityDifference(relighter.solution(), model.solve(swung(scene, 10.0f, 0.0f))),
      0.005);
}

// On a fixed mesh the precomputed transfer takes the place of shooting: each change bounces out
// in one step, to the same answer as a fresh solve (and no unshot light left).
TEST(Relighter, ThePrecomputedTransferMatchesFreshSolves) {
  const Scene scene = loadScene("cornell-spot");
  PatchRadiositySettings s = smallSettings();
  s.refineLevels = 0;  // a mesh the transfer stays valid for
  const PatchModel model(scene, s);
  Relighter relighter(model, scene.lights, {.transferPatches = 5000});
  for (int k = 1; k <= 6; ++k) {
    const std::vector<Light> lights = swung(scene, 5.0f * float(k), 10.0f * float(k));
    const RelightStats& stats = relighter.relight(lights);
    EXPECT_EQ(stats.unshot, 0.0);
    EXPECT_LE(largestRadiosityDifference(relighter.solution(), model.solve(lights)), 0.005)
        << "move " << k;
  }
}

// A dimmer on glowing surfaces: the Cornell box's lamp (its emitting material) at 30% relit
// equals a fresh solve of the box with the lamp's emission at 30%, and its own patches show it.
TEST(Relighter, DimmingAGlowingSurfaceMatchesAFreshSolve) {
  const Scene scene = loadScene("cornell");
  const PatchModel model(scene, smallSettings());
  Relighter relighter(model, scene.lights);
  std::vector<Color> scales(scene.materials.size(), Color(1.0f));
  uint32_t lamp = 0;
  while (!scene.materials[lamp].emits()) ++lamp;
  scales[lamp] = Color(0.3f);
  const RelightStats& stats = relighter.relight(scene.lights, scales);
  EXPECT_GT(stats.patchesUpdated, 0u);
  Scene dimmed = scene;
  dimmed.materials[lamp].emission *= 0.3f;
  const PatchRadiosity fresh = PatchModel(dimmed, smallSettings()).solve(dimmed.lights);
  EXPECT_LE(largestRadiosityDifference(relighter.solution(), fresh), 0.005);
  EXPECT_EQ(relighter.solution().emissionScales()[lamp], Color(0.3f));
  EXPECT_THROW(relighter.relight(scene.lights, std::vector<Color>(1, Color(1.0f))),
               std::invalid_argument);
}

// Dimming to a quarter changes no patch's place in the quadtree, and the answer is a quarter of
// the spot's light plus nothing else (the scene has no other light).
TEST(Relighter, DimmingScalesTheSolutionWithoutNewPatches) {
  const Scene scene = loadScene("cornell-spot");
  const PatchModel model(scene, smallSettings());
  Relighter relighter(model, scene.lights);
  const PatchRadiosity full = model.solve(scene.lights);
  std::vector<Light> dimmed = scene.lights;
  dimmed[0].intensity *= 0.25f;
  const RelightStats& stats = relighter.relight(dimmed);
  EXPECT_FALSE(stats.meshChanged);
  EXPECT_EQ(stats.lightsChanged, 1u);
  double worst = 0.0, mean = 0.0;
  for (size_t p = 0; p < full.elementCount(); ++p) {
    const Color expected = 0.25f * full.element(p).radiosity;
    worst = std::max(
        worst,
        double(maxComponent(glm::abs(relighter.solution().element(p).radiosity - expected))));
    mean += maxComponent(expected) / double(full.elementCount());
  }
  EXPECT_LE(worst, 0.005 * mean);
}

TEST(Relighter, TheSameLightsChangeNothing) {
  const Scene scene = loadScene("cornell-spot");
  const PatchModel model(scene, smallSettings());
  Relighter relighter(model, scene.lights);
  const RelightStats& stats = relighter.relight(scene.lights);
  EXPECT_EQ(stats.lightsChanged, 0u);
  EXPECT_EQ(stats.patchesUpdated, 0u);
  EXPECT_FALSE(stats.meshChanged);
  EXPECT_LE(largestRadiosityDifference(relighter.solution(), model.solve(scene.lights)), 0.005);
}

TEST(Relighter, NeedsTheMasterTable) {
  const Scene scene = loadScene("cornell-spot");
  PatchRadiositySettings s = smallSettings();
  s.estimator = PatchFormFactorEstimator::Pairwise;
  s.formFactorRays = 4;
  const PatchModel model(scene, s);
  EXPECT_THROW(Relighter(model, scene.lights), InputError);
}

}  // namespace
}  // namespace rad
