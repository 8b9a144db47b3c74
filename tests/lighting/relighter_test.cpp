// Relighting: a solution brought to moved lights by shooting the change must be the solution a
// fresh solve of those lights gives, after any sequence of moves, without drifting.
#include <gtest/gtest.h>
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

}  // namespace
}  // namespace rad
