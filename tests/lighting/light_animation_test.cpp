// Lights over time: spins and keyframed paths evaluated at an instant, checked by where the
// light lands, not by echoing the interpolation.
#include <gtest/gtest.h>
#include <radiosity/ray_caster.h>
#include <radiosity/scene.h>

#include <cmath>
#include <glm/gtc/constants.hpp>

#include "light_test_scenes.h"
#include "lighting/direct_lighting.h"

namespace rad {
namespace {

constexpr float kHeight = 1.5f, kOuterDeg = 20.0f;

Light spinningSpot() {
  Light spot = test::downSpot(Vec3(0.0f, kHeight, 0.0f), Color(5.0f), 10.0f, kOuterDeg);
  spot.spinDegPerS = Vec3(0.0f, 0.0f, 90.0f);  // a quarter turn a second about +z
  return spot;
}

// The lit stretch of the floor's x axis: [first, last] x where the light arrives.
std::pair<float, float> litStretch(const Scene& scene, const Light& light) {
  const RayCaster caster(scene);
  const std::vector<Light> lights{light};
  const DirectLighting direct(scene, caster, lights);
  float first = 1e9f, last = -1e9f;
  for (float x = -3.9f; x <= 3.9f; x += 0.002f) {
    if (maxComponent(direct.fromLights(Vec3(x, 0.0f, 0.0f), Vec3(0, 1, 0))) <= 0.0f) continue;
    first = std::min(first, x);
    last = std::max(last, x);
  }
  return {first, last};
}

// At t = 0.5 s the spin has turned the spot 45 degrees from straight down toward +x (a
// right-handed turn about +z takes -y to +x), so the beam's edges meet the floor at
// h tan(45 - outer) and h tan(45 + outer) along +x.
TEST(LightAnimation, SpinningSpotLandsWhereTheSpinPredicts) {
  const Light spot = spinningSpot();
  const Scene scene = test::floorUnderLight(4.0f, spot);
  const auto [first, last] = litStretch(scene, spot.at(0.5));
  EXPECT_NEAR(first, kHeight * std::tan(glm::radians(45.0f - kOuterDeg)), 0.01f);
  EXPECT_NEAR(last, kHeight * std::tan(glm::radians(45.0f + kOuterDeg)), 0.01f);
  // At t = 0 it points straight down: the beam is centred under the light.
  const auto [first0, last0] = litStretch(scene, spot.at(0.0));
  EXPECT_NEAR(first0, -last0, 0.01f);
}

TEST(LightAnimation, PathInterpolatesEachFieldBetweenTheKeyframesThatSetIt) {
  Light light = spinningSpot();
  light.spinDegPerS = Vec3(0.0f);
  light.path = {{0.0, Vec3(0, 2, 0), Vec3(0, -1, 0), Color(1.0f)},
                {1.0, Vec3(2, 2, 0), std::nullopt, std::nullopt},
                {2.0, std::nullopt, Vec3(1, 0, 0), Color(3.0f)}};
  const Light quarter = light.at(0.5);
  EXPECT_NEAR(quarter.position.x, 1.0f, 1e-6f);
  // Direction from the keyframes at 0 and 2: a quarter of the way along the great circle.
  const float angle = glm::radians(22.5f);
  EXPECT_NEAR(quarter.direction.x, std::sin(angle), 1e-5f);
  EXPECT_NEAR(quarter.direction.y, -std::cos(angle), 1e-5f);
  EXPECT_NEAR(light.at(1.0).intensity.r, 2.0f, 1e-5f);
  // Held outside the keyframes.
  EXPECT_EQ(light.at(-1.0).position, Vec3(0, 2, 0));
  EXPECT_EQ(light.at(5.0).position, Vec3(2, 2, 0));
  EXPECT_EQ(light.at(5.0).intensity, Color(3.0f));
  EXPECT_NEAR(glm::length(light.at(1.3).direction), 1.0f, 1e-6f);
  EXPECT_TRUE(light.animated());
  EXPECT_FALSE(test::pointLight(Vec3(0.0f), Color(1.0f)).animated());
}

}  // namespace
}  // namespace rad
