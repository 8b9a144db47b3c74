// Rays through surfaces that are not opaque (geometry/coverage_filter.h): a Mask checkerboard's
// shadow on a floor under a point light is the closed form I cos / d^2 where a ray passes a
// cut-away texel and 0 elsewhere, point by point; a camera ray sees the floor through a hole; a
// Blend sheet of alpha 0.3 and a pane of transmission 0.9 stop the shares 0.3 and 0.1 of rays,
// the same rays each time.
#include <gtest/gtest.h>
#include <radiosity/ray_caster.h>
#include <radiosity/scene_builder.h>

#include <cmath>
#include <memory>
#include <vector>

#include "core/rng.h"
#include "lighting/direct_lighting.h"

namespace rad {
namespace {

constexpr int kTexels = 8;

// An 8 x 8 checkerboard of alpha: texel (i, j) transparent where i + j is even.
bool holeAt(int i, int j) {
  return (i + j) % 2 == 0;
}

std::shared_ptr<const Texture> checker() {
  std::vector<Color> colour(kTexels * kTexels, Color(0.5f));
  std::vector<float> alpha;
  for (int j = 0; j < kTexels; ++j)
    for (int i = 0; i < kTexels; ++i) alpha.push_back(holeAt(i, j) ? 0.0f : 1.0f);
  return std::make_shared<const Texture>(kTexels, kTexels, std::move(colour), "checker",
                                         std::move(alpha));
}

// A floor [-2, 2]^2 at z = 0 facing +z (object 0) under a sheet [-1, 1]^2 at z = 1 facing -z
// (object 1) of the material `sheet`, its texture coordinates (x + 1, y + 1) / 2.
Scene floorUnderSheet(Material sheet) {
  SceneBuilder b("sheet");
  const uint32_t grey = b.addMaterial(Material{});
  const uint32_t m = b.addMaterial(std::move(sheet));
  const uint32_t floor = b.addObject("floor"), top = b.addObject("sheet");
  std::vector<uint32_t> ids;
  for (Vec2 c : {Vec2(-2, -2), Vec2(2, -2), Vec2(2, 2), Vec2(-2, 2)})
    ids.push_back(b.addVertex(Vec3(c, 0.0f), Vec2(0.0f), "floor"));
  b.addPolygon(ids, grey, floor, "floor");
  ids.clear();
  for (Vec2 c : {Vec2(-1, -1), Vec2(-1, 1), Vec2(1, 1), Vec2(1, -1)})  // CCW about -z
    ids.push_back(b.addVertex(Vec3(c, 1.0f), (c + Vec2(1.0f)) * 0.5f, "sheet"));
  b.addPolygon(ids, m, top, "sheet");
  return b.build();
}

Material maskedChecker() {
  Material m;
  m.alphaMode = AlphaMode::Mask;
  m.alphaTexture.texture = checker();
  m.alphaTexture.wrapU = m.alphaTexture.wrapV = TextureWrap::ClampToEdge;
  return m;
}

TEST(CoverageFilter, MaskCheckerShadowIsTheClosedFormThroughItsHolesOnly) {
  const Scene scene = floorUnderSheet(maskedChecker());
  const RayCaster caster(scene);
  Light light;
  light.position = Vec3(0, 0, 2);
  light.intensity = Color(1.0f);
  const std::vector<Light> lights{light};
  const DirectLighting direct(scene, caster, lights);
  // Floor points at the centres of a 64 x 64 grid over [-2, 2]^2: the ray to the light crosses
  // the sheet at (x, y) / 2, 8 points a texel a side, never on a texel's edge.
  double through = 0.0, open = 0.0;
  for (int gy = 0; gy < 64; ++gy)
    for (int gx = 0; gx < 64; ++gx) {
      const Vec3 p(-2.0f + (float(gx) + 0.5f) / 16.0f, -2.0f + (float(gy) + 0.5f) / 16.0f, 0.0f);
      const Vec3 d = light.position - p;
      const float d2 = glm::dot(d, d);
      const double closedForm = d.z / std::sqrt(d2) / d2;  // I cos / d^2, I = 1
      const bool hole = holeAt(gx / 8, gy / 8);
      const float e = direct.fromLight(light, p, Vec3(0, 0, 1)).g;
      EXPECT_NEAR(e, hole ? closedForm : 0.0, 1e-5 * closedForm) << p.x << ", " << p.y;
      through += e;
      open += closedForm;
    }
  // The checker's mirror image swaps holes and texels: exactly half of the light passes.
  EXPECT_NEAR(through / open, 0.5, 1e-5);
}

TEST(CoverageFilter, CameraRaySeesTheFloorThroughACutOut) {
  const Scene scene = floorUnderSheet(maskedChecker());
  const RayCaster caster(scene);
  // Down from z = 2 through texel (0, 0) (a hole) and texel (1, 0) (kept).
  const Hit hole = caster.intersect(Ray{Vec3(-0.9f, -0.9f, 2.0f), Vec3(0, 0, -1)});
  const Hit kept = caster.intersect(Ray{Vec3(-0.6f, -0.9f, 2.0f), Vec3(0, 0, -1)});
  ASSERT_TRUE(hole.valid() && kept.valid());
  EXPECT_EQ(scene.faceOf(hole.triangle).object, 0u);
  EXPECT_FLOAT_EQ(hole.distance, 2.0f);
  EXPECT_EQ(scene.faceOf(kept.triangle).object, 1u);
  EXPECT_FLOAT_EQ(kept.distance, 1.0f);
  // The sheet's own normal (its front faces the floor, -z: a ray from above meets its back),
  // not that of the primitive of the same index in the opaque geometry.
  EXPECT_EQ(kept.geometricNormal, Vec3(0, 0, -1));
  EXPECT_FALSE(kept.frontFace);
  EXPECT_EQ(hole.geometricNormal, Vec3(0, 0, 1));
}

// The share of 100,000 rays from random floor points to random points above the sheet that it
// stops; the same rays give the same answers.
double stoppedShare(const Scene& scene) {
  const RayCaster caster(scene);
  Rng rng(7, 1);
  std::vector<Ray> rays;
  for (int k = 0; k < 100000; ++k) {
    const Vec3 from(rng.uniform() - 0.5f, rng.uniform() - 0.5f, 0.0f);
    const Vec3 to(rng.uniform() - 0.5f, rng.uniform() - 0.5f, 2.0f);
    rays.push_back({from, to - from, 1e-4f, 1.0f});
  }
  std::vector<uint8_t> stopped(rays.size()), again(rays.size());
  caster.occluded(rays, stopped);
  caster.occluded(rays, again);
  EXPECT_EQ(stopped, again);
  for (size_t k = 0; k < 100; ++k) EXPECT_EQ(caster.occluded(rays[k]), bool(stopped[k]));
  double sum = 0.0;
  for (uint8_t s : stopped) sum += s;
  return sum / double(rays.size());
}

TEST(CoverageFilter, BlendSheetStopsAlphaAndGlassOneMinusTransmission) {
  // Binomial: 4 standard deviations, sqrt(p (1 - p) / 1e5), are 0.0058 at p = 0.3, 0.0038 at 0.1.
  Material blend;
  blend.alphaMode = AlphaMode::Blend;
  blend.alpha = 0.3f;
  EXPECT_NEAR(stoppedShare(floorUnderSheet(blend)), 0.3, 0.0058);
  Material glass;
  glass.transmission = 0.9f;
  EXPECT_NEAR(stoppedShare(floorUnderSheet(glass)), 0.1, 0.0038);
}

}  // namespace
}  // namespace rad
