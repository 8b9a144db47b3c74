// DirectLighting at single points: the inverse-square cosine law, the spot's cone, shadows, and
// the emitters' estimate against the closed-form view factor.
#include "lighting/direct_lighting.h"

#include <gtest/gtest.h>
#include <radiosity/ray_caster.h>

#include <cmath>

#include "core/rng.h"
#include "light_test_scenes.h"

namespace rad {
namespace {

// A point light: E = I cos(theta) / d^2 at any floor point (theta from the floor's normal;
// docs/references.md 3.5).
TEST(DirectLighting, PointLightFollowsTheInverseSquareCosineLaw) {
  const Vec3 light(0.2f, 1.5f, -0.3f);
  const Scene scene = test::floorUnderLight(2.0f, test::pointLight(light, Color(7.0f, 3.0f, 1.0f)));
  const RayCaster caster(scene);
  const DirectLighting direct(scene, caster);
  for (const Vec3 p : {Vec3(0.0f), Vec3(1.5f, 0.0f, 1.0f), Vec3(-1.9f, 0.0f, -1.9f)}) {
    const Vec3 d = light - p;
    const double cosTheta = d.y / glm::length(d);
    const double expected = 7.0 * cosTheta / glm::dot(d, d);
    EXPECT_NEAR(direct.fromLights(p, Vec3(0, 1, 0)).r, expected, 1e-5 * expected);
  }
  // Facing away: nothing.
  EXPECT_EQ(direct.fromLights(Vec3(0.0f), Vec3(0, -1, 0)), Color(0.0f));
}

// A spot aimed straight down: as a point light inside the inner cone, zero beyond the outer
// cone, and falling monotonically (relative to the point light) between.
TEST(DirectLighting, SpotIsAPointLightInsideItsConeAndDarkOutside) {
  const float height = 1.0f;
  Light spot = test::pointLight(Vec3(0, height, 0), Color(5.0f));
  spot.type = LightType::Spot;
  spot.direction = Vec3(0, -1, 0);
  spot.innerAngleDeg = 20.0f;
  spot.outerAngleDeg = 30.0f;
  const Scene scene = test::floorUnderLight(3.0f, spot);
  const RayCaster caster(scene);
  const DirectLighting direct(scene, caster);
  double previousShare = 1.0;
  for (double deg = 0.0; deg < 40.0; deg += 0.5) {
    const float r = height * float(std::tan(glm::radians(deg)));
    const Vec3 p(r, 0.0f, 0.0f);
    const double pointLight = 5.0 * std::pow(std::cos(glm::radians(deg)), 3.0) / (height * height);
    const double e = direct.fromLights(p, Vec3(0, 1, 0)).g;
    const double share = e / pointLight;
    if (deg < 19.9) {
      EXPECT_NEAR(share, 1.0, 1e-4) << deg << " degrees";
    }
    if (deg > 30.1) {
      EXPECT_EQ(e, 0.0) << deg << " degrees";
    }
    EXPECT_LE(share, previousShare + 1e-6) << deg << " degrees";
    EXPECT_NEAR(share, test::spotFalloff(std::cos(glm::radians(deg)), 20.0, 30.0), 1e-4);
    previousShare = share;
  }
}

// A square occluder: points under it are dark, points beside its shadow are lit.
TEST(DirectLighting, OccluderShadowsThePointsBehindIt) {
  const Scene scene =
      test::floorUnderLight(2.0f, test::pointLight(Vec3(0, 2, 0), Color(1.0f)), 0.3f, 1.0f);
  const RayCaster caster(scene);
  const DirectLighting direct(scene, caster);
  EXPECT_EQ(direct.fromLights(Vec3(0.59f, 0.0f, 0.0f), Vec3(0, 1, 0)), Color(0.0f));
  EXPECT_GT(direct.fromLights(Vec3(0.61f, 0.0f, 0.0f), Vec3(0, 1, 0)).g, 0.0f);
  EXPECT_TRUE(direct.visible(Vec3(1.0f, 0.0f, 0.0f), Vec3(0, 1, 0), Vec3(0, 2, 0)));
  EXPECT_FALSE(direct.visible(Vec3(0.0f), Vec3(0, 1, 0), Vec3(0, 2, 0)));
}

// Emissive triangles: the mean of many one-sample estimates at a point under a parallel square
// emitter is pi Ke F (F by the corner formula, docs/references.md 1(d)).
TEST(DirectLighting, EmitterEstimateAveragesToTheViewFactor) {
  SceneBuilder b("emitter");
  const uint32_t lamp = b.addMaterial({"lamp", Color(0.0f), Color(2.0f), false});
  const uint32_t object = b.addObject("lamp");
  test::addQuadFacing(b, test::axisSquare(Vec3(0, 1, 0), 1, 1.0f), Vec3(0, -1, 0), lamp, object);
  const Scene scene = b.build();
  const RayCaster caster(scene);
  const DirectLighting direct(scene, caster);
  ASSERT_TRUE(direct.hasEmitters());
  ASSERT_FALSE(direct.hasLights());
  Rng rng(1, 0);
  double sum = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) sum += direct.sampleEmitters(Vec3(0.0f), Vec3(0, 1, 0), rng).g;
  const double f = test::pointToParallelRectangleF(0, 0, -0.5, 0.5, -0.5, 0.5, 1.0);
  const double expected = glm::pi<double>() * 2.0 * f;
  EXPECT_NEAR(sum / n, expected, 0.01 * expected);
}

}  // namespace
}  // namespace rad
