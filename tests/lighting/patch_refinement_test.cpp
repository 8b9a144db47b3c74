// Adaptive subdivision of the patch mesh for point, spot and IES lights: where the fine patches
// go, that they make the answer closer to the closed form, and that shading stays continuous
// where fine patches meet coarse ones.
#include <gtest/gtest.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/ray_caster.h>

#include <array>
#include <cmath>
#include <limits>
#include <map>

#include "light_test_scenes.h"
#include "lighting/direct_lighting.h"
#include "patch/light_refinement.h"

namespace rad {
namespace {

constexpr float kHalf = 2.0f, kHeight = 1.5f, kOuterDeg = 30.0f;

Light downSpot() {
  return test::downSpot(Vec3(0.0f, kHeight, 0.0f), Color(6.0f), 20.0f, kOuterDeg);
}

// The beam's edge on the floor is the circle of radius h tan(outer angle). Every patch split to
// the finest level lies within one base patch (its diagonal) of it: the edge test splits the
// patches the circle crosses, the neighbour test those next to them, whose light differs by more
// than half where the smoothstep falls to 0.
TEST(PatchRefinement, FinestPatchesHugTheBeamEdge) {
  const Scene scene = test::floorUnderLight(kHalf, downSpot());
  const RayCaster caster(scene);
  PatchMesh mesh(scene, {0.25f, 0});
  const size_t base = mesh.size();
  const int baseDepth = mesh.roots()[0].baseDepth;
  const LightRefinement r = refineForLights(mesh, DirectLighting(scene, caster), {2, 0.5f, 16});
  EXPECT_GT(mesh.size(), base);
  EXPECT_EQ(r.basePatches, base);
  EXPECT_EQ(r.direct.size(), mesh.size());
  const float edgeRadius = kHeight * std::tan(glm::radians(kOuterDeg));
  const float basePatch = 0.25f * std::sqrt(2.0f);  // a base patch's diagonal
  size_t finest = 0;
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    if (mesh.nodeOf(p).depth != baseDepth + 2) continue;
    ++finest;
    std::array<Vec3, 4> corners;
    const int n = mesh.corners(p, corners);
    float fromEdge = std::numeric_limits<float>::max();
    for (int k = 0; k < n; ++k)
      fromEdge = std::min(fromEdge, std::abs(std::hypot(corners[k].x, corners[k].z) - edgeRadius));
    const Vec3 c = mesh.patches()[p].centroid;
    EXPECT_LE(fromEdge, basePatch) << "patch at (" << c.x << ", " << c.z << ")";
  }
  // The circle's length over the fine patches' size: most of the ring is refined.
  EXPECT_GT(finest, size_t(2 * glm::pi<float>() * edgeRadius / (0.25f / 4.0f)));
}

// Patches lit at their centroid alone, so that the base mesh's error shows.
PatchRadiositySettings centroidLit(float patchSize, int refineLevels) {
  PatchRadiositySettings s;
  s.patchSize = patchSize;
  s.cacheDir.clear();
  s.lightSamples = 1;
  s.refineLevels = refineLevels;
  return s;
}

// With one point per patch (its centroid) a beam edge gives each patch it crosses all or
// nothing; refinement brackets the edge with smaller patches, and the floor's mean irradiance
// comes closer to the 2000 x 2000 integral of the falloff than without, at the same base size.
TEST(PatchRefinement, RefinedSpotIsCloserToTheIntegral) {
  const Scene scene = test::floorUnderLight(kHalf, downSpot());
  const double expected = test::meanFloorIrradiance(
      kHalf, Vec3d(0.0, kHeight, 0.0), 2000,
      [](const Vec3d& toward) { return 6.0 * test::spotFalloff(-toward.y, 20.0, kOuterDeg); });
  auto error = [&](int levels) {
    const PatchRadiosity solution(scene, centroidLit(0.5f, levels));
    return std::abs(solution.objectRadiometry()[0].meanIrradiance.g / expected - 1.0);
  };
  const double coarse = error(0), refined = error(3);
  EXPECT_LT(refined, 0.5 * coarse) << "unrefined " << coarse << ", refined " << refined;
}

// A hard shadow: the square occluder's shadow edges are split, and the mean irradiance (I
// Omega / A by the corner formula) is closer than without refinement at the same base size.
TEST(PatchRefinement, RefinedShadowIsCloserToTheClosedForm) {
  const Scene scene =
      test::floorUnderLight(kHalf, test::pointLight(Vec3(0, 2, 0), Color(4.0f)), 0.3f, 1.0f);
  const double shadowHalf = 0.6;  // the occluder's 0.3 projected from 2 over its height 1
  const double omega =
      test::rectangleSolidAngle(0, 0, -kHalf, kHalf, -kHalf, kHalf, 2.0) -
      test::rectangleSolidAngle(0, 0, -shadowHalf, shadowHalf, -shadowHalf, shadowHalf, 2.0);
  const double expected = 4.0 * omega / (4.0 * kHalf * kHalf);
  auto solve = [&](int levels) { return PatchRadiosity(scene, centroidLit(0.45f, levels)); };
  const PatchRadiosity coarse = solve(0), refined = solve(3);
  EXPECT_GT(refined.stats().patches, coarse.stats().patches);
  EXPECT_EQ(refined.stats().basePatches, coarse.stats().patches);
  auto error = [&](const PatchRadiosity& s) {
    for (const ObjectRadiometry& o : s.objectRadiometry())
      if (o.name == "floor") return std::abs(o.meanIrradiance.g / expected - 1.0);
    return 1.0;
  };
  EXPECT_LT(error(refined), 0.5 * error(coarse))
      << "unrefined " << error(coarse) << ", refined " << error(refined);
}

// Where a fine patch meets a coarse one, smooth shading has no step: radiance along a line
// across the refined floor changes by at most a little between points 1e-4 apart, though patches
// of three sizes meet on it. Flat shading, for contrast, steps at every patch border.
TEST(PatchRefinement, SmoothShadingHasNoCracksAtTJunctions) {
  const Scene scene = test::floorUnderLight(kHalf, downSpot());
  PatchRadiositySettings s;
  s.patchSize = 0.25f;
  s.cacheDir.clear();
  s.refineLevels = 2;
  auto largestStep = [&](const PatchRadiosity& solution) {
    float largest = 0.0f, previous = -1.0f;
    for (float x = -1.9f; x < 1.9f; x += 1e-4f) {
      const SurfaceHit hit{Vec3(x, 0.0f, 0.013f), Vec3(0, 1, 0), 0, true};
      const float l = solution.radiance(hit).g;
      if (previous >= 0.0f) largest = std::max(largest, std::abs(l - previous));
      previous = l;
    }
    return largest;
  };
  const PatchRadiosity smooth(scene, s);
  ASSERT_GT(smooth.stats().refinedSplits, 0u);
  s.shading = PatchShading::Flat;
  const PatchRadiosity flat(scene, s);
  const float peak = smooth.radiance({Vec3(0.0f), Vec3(0, 1, 0), 0, true}).g;
  EXPECT_LT(largestStep(smooth), 2e-3f * peak);
  EXPECT_GT(largestStep(flat), 10.0f * largestStep(smooth));
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

// The lit mesh of a refined floor has no T-junctions: a coarse patch takes its finer neighbours'
// vertices on its edges into its outline, so every edge inside the floor is shared by two
// triangles and the edges used once are the floor's outline (length 4 x 4).
TEST(PatchRefinement, LitMeshHasNoTJunctions) {
  const Scene scene = test::floorUnderLight(kHalf, downSpot());
  PatchRadiositySettings s;
  s.patchSize = 0.25f;
  s.cacheDir.clear();
  for (PatchShading shading : {PatchShading::Smooth, PatchShading::Flat}) {
    s.shading = shading;
    const PatchRadiosity solution(scene, s);
    ASSERT_GT(solution.stats().refinedSplits, 0u);
    const LitMesh mesh = solution.litMesh();
    // Edges by their end positions (flat shading does not share vertices).
    std::map<std::pair<std::array<float, 3>, std::array<float, 3>>, int> uses;
    auto at = [&](uint32_t i) {
      const Vec3& p = mesh.positions[i];
      return std::array<float, 3>{p.x, p.y, p.z};
    };
    for (size_t t = 0; t < mesh.indices.size(); t += 3)
      for (int k = 0; k < 3; ++k) {
        auto a = at(mesh.indices[t + k]), b = at(mesh.indices[t + (k + 1) % 3]);
        if (b < a) std::swap(a, b);
        ++uses[{a, b}];
      }
    double once = 0.0;
    for (const auto& [edge, count] : uses) {
      EXPECT_LE(count, 2);
      if (count == 1)
        once += glm::distance(Vec3(edge.first[0], edge.first[1], edge.first[2]),
                              Vec3(edge.second[0], edge.second[1], edge.second[2]));
    }
    EXPECT_NEAR(once, 8.0 * kHalf, 1e-3) << (shading == PatchShading::Smooth ? "smooth" : "flat");
  }
}

}  // namespace
}  // namespace rad
