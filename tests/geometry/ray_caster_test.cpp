// RayCaster against hand-placed triangles whose hits are worked out by hand.
#include <gtest/gtest.h>
#include <radiosity/ray_caster.h>
#include <radiosity/scene_builder.h>
#include <tbb/parallel_for.h>

#include <array>
#include <vector>

#include "core/rng.h"

namespace rad {
namespace {

// Two right triangles with legs 1 along x and y: triangle 0 in z = 0, triangle 1 in z = 2, both
// counter-clockwise about +z, so their front normal is +z.
Scene twoTriangles() {
  SceneBuilder b("two triangles");
  const uint32_t m = b.addMaterial(Material{});
  const uint32_t o = b.addObject("tris");
  for (float z : {0.0f, 2.0f}) {
    const std::array<uint32_t, 3> c{b.addVertex({0, 0, z}, "t"), b.addVertex({1, 0, z}, "t"),
                                    b.addVertex({0, 1, z}, "t")};
    b.addPolygon(c, m, o, "t");
  }
  return b.build();
}

Ray makeRay(Vec3 origin, Vec3 direction, float tNear = 0.0f,
            float tFar = std::numeric_limits<float>::infinity()) {
  return Ray{origin, direction, tNear, tFar};
}

TEST(RayCaster, ClosestHitDistanceBarycentricAndFrontFace) {
  const Scene scene = twoTriangles();
  ASSERT_EQ(scene.triangles.size(), 2u);
  const RayCaster caster(scene);
  // From z = 5 down: the upper triangle (1) at t = 3; point (0.6, 0.3) = 0.1 p0 + 0.6 p1 + 0.3 p2.
  const Hit hit = caster.intersect(makeRay({0.6f, 0.3f, 5.0f}, {0, 0, -1}));
  ASSERT_TRUE(hit.valid());
  EXPECT_EQ(hit.triangle, 1u);
  EXPECT_NEAR(hit.distance, 3.0f, 1e-5f);
  EXPECT_NEAR(hit.barycentric.x, 0.6f, 1e-5f);
  EXPECT_NEAR(hit.barycentric.y, 0.3f, 1e-5f);
  EXPECT_NEAR(hit.geometricNormal.z, 1.0f, 1e-6f);
  EXPECT_TRUE(hit.frontFace);
}

TEST(RayCaster, BackFaceHitFromBelow) {
  const RayCaster caster(twoTriangles());
  // Going up from z = -1 the lower triangle (0) is met first, on its back side, at t = 1.
  const Hit hit = caster.intersect(makeRay({0.25f, 0.25f, -1.0f}, {0, 0, 1}));
  ASSERT_TRUE(hit.valid());
  EXPECT_EQ(hit.triangle, 0u);
  EXPECT_NEAR(hit.distance, 1.0f, 1e-5f);
  EXPECT_FALSE(hit.frontFace);
  EXPECT_NEAR(hit.geometricNormal.z, 1.0f, 1e-6f);  // still the front normal
}

TEST(RayCaster, MissAndDistanceLimits) {
  const RayCaster caster(twoTriangles());
  EXPECT_FALSE(caster.intersect(makeRay({2, 2, 5}, {0, 0, -1})).valid());       // beside both
  EXPECT_FALSE(caster.intersect(makeRay({0.2f, 0.2f, 5}, {0, 0, 1})).valid());  // away
  // tFar short of the first triangle (t = 3): nothing.
  EXPECT_FALSE(caster.intersect(makeRay({0.2f, 0.2f, 5}, {0, 0, -1}, 0.0f, 2.9f)).valid());
  // tNear past the first triangle: the lower one at t = 5.
  const Hit past = caster.intersect(makeRay({0.2f, 0.2f, 5}, {0, 0, -1}, 3.5f));
  ASSERT_TRUE(past.valid());
  EXPECT_EQ(past.triangle, 0u);
  EXPECT_NEAR(past.distance, 5.0f, 1e-5f);
}

TEST(RayCaster, OcclusionFromBothSides) {
  const RayCaster caster(twoTriangles());
  EXPECT_FALSE(caster.occluded(makeRay({0.2f, 0.2f, 5}, {0, 0, -1}, 0.0f, 2.5f)));
  EXPECT_TRUE(caster.occluded(makeRay({0.2f, 0.2f, 5}, {0, 0, -1}, 0.0f, 3.5f)));
  EXPECT_TRUE(caster.occluded(makeRay({0.2f, 0.2f, -1}, {0, 0, 1})));  // back side blocks too
  EXPECT_FALSE(caster.occluded(makeRay({2, 2, -1}, {0, 0, 1})));
  // Between the triangles, limited to the gap: free.
  EXPECT_FALSE(caster.occluded(makeRay({0.2f, 0.2f, 0.5f}, {0, 0, 1}, 0.0f, 1.0f)));
}

TEST(RayCaster, EmptySceneMissesEverything) {
  const RayCaster caster(Scene{});
  EXPECT_FALSE(caster.intersect(makeRay({0, 0, 0}, {0, 0, 1})).valid());
  EXPECT_FALSE(caster.occluded(makeRay({0, 0, 0}, {0, 0, 1})));
}

// Rays from random points of a box around the triangles toward random points of the triangles'
// plane region: a mix of hits on both triangles, both sides, and misses.
std::vector<Ray> randomRays(size_t n) {
  Rng rng(7, 3);
  std::vector<Ray> rays(n);
  for (Ray& r : rays) {
    const Vec3 from(rng.uniform() * 3 - 1, rng.uniform() * 3 - 1, rng.uniform() * 6 - 2);
    const Vec3 to(rng.uniform() * 1.5f - 0.25f, rng.uniform() * 1.5f - 0.25f, rng.uniform() * 2);
    r = makeRay(from, glm::normalize(to - from), 0.0f, 2.0f + 4.0f * rng.uniform());
  }
  return rays;
}

TEST(RayCaster, BatchEqualsSingle) {
  const RayCaster caster(twoTriangles());
  const std::vector<Ray> rays = randomRays(1000);
  std::vector<Hit> hits(rays.size());
  std::vector<uint8_t> blocked(rays.size());
  caster.intersect(rays, hits);
  caster.occluded(rays, blocked);
  size_t hitCount = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const Hit single = caster.intersect(rays[i]);
    ASSERT_EQ(hits[i].triangle, single.triangle) << i;
    if (single.valid()) {
      ++hitCount;
      EXPECT_FLOAT_EQ(hits[i].distance, single.distance);
      EXPECT_EQ(hits[i].frontFace, single.frontFace);
    }
    EXPECT_EQ(bool(blocked[i]), caster.occluded(rays[i])) << i;
    EXPECT_EQ(bool(blocked[i]), single.valid()) << i;  // same [tNear, tFar] for both queries
  }
  EXPECT_GT(hitCount, 100u);
  EXPECT_LT(hitCount, 900u);
  EXPECT_EQ(caster.raysCast(), 4 * rays.size());
}

TEST(RayCaster, ConcurrentQueriesAgree) {
  const RayCaster caster(twoTriangles());
  const std::vector<Ray> rays = randomRays(20000);
  std::vector<uint32_t> serial(rays.size()), parallel(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) serial[i] = caster.intersect(rays[i]).triangle;
  tbb::parallel_for(size_t(0), rays.size(),
                    [&](size_t i) { parallel[i] = caster.intersect(rays[i]).triangle; });
  EXPECT_EQ(serial, parallel);
  EXPECT_EQ(caster.raysCast(), 2 * rays.size());
}

TEST(RayCaster, MovedCasterStillWorks) {
  RayCaster a(twoTriangles());
  RayCaster b(std::move(a));
  EXPECT_TRUE(b.intersect(makeRay({0.2f, 0.2f, 5}, {0, 0, -1})).valid());
}

}  // namespace
}  // namespace rad
