// Built-in scenes: the Cornell box against the reference OBJ (tests/data/scene/cornell), areas
// from docs/references.md 2.3 / 2.4; room:N scaling.

#include <gtest/gtest.h>
#include <radiosity/ray_caster.h>
#include <radiosity/scene_loader.h>

#include "scene_summary.h"

namespace rad {
namespace {

using test::kData;

TEST(BuiltinScenes, CornellMatchesReferenceObj) {
  const Scene builtin = loadScene("cornell");
  const Scene reference = loadScene(kData + "cornell/cornell_box.obj");
  EXPECT_EQ(builtin.triangles.size(), reference.triangles.size());
  EXPECT_EQ(builtin.triangles.size(), 46u);  // docs/references.md 2.4: 46 triangles
  const auto a = test::summarize(builtin, 0.01), b = test::summarize(reference, 0.01);
  ASSERT_EQ(a.size(), 8u);
  for (const auto& [name, o] : b) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(a.count(name));
    EXPECT_NEAR(a.at(name).area, o.area, 1e-6 * o.area);
    EXPECT_EQ(a.at(name).positions, o.positions);
    EXPECT_EQ(a.at(name).material->rho, o.material->rho);
    EXPECT_EQ(a.at(name).material->emission, o.material->emission);
    for (const auto& [normal, area] : o.areaByNormal)
      EXPECT_NEAR(a.at(name).areaByNormal.at(normal), area, 1e-6 * o.area);
  }
  // docs/references.md 2.3 / 2.4 areas (mm^2).
  EXPECT_NEAR(a.at("floor").area, 308231.0, 0.5);
  EXPECT_NEAR(a.at("back_wall").area, 303376.6, 0.5);
  EXPECT_NEAR(a.at("ceiling").area, 297265.2, 0.5);
  EXPECT_NEAR(a.at("light").area, 13650.0, 0.05);
  EXPECT_NEAR(a.at("left_wall_red").area, 306904.5, 0.5);
  EXPECT_NEAR(a.at("short_block").area, 137348.9, 0.5);
  EXPECT_NEAR(a.at("tall_block").area, 247030.4, 0.5);
  double total = 0.0;
  for (const auto& [name, o] : a) total += o.area;
  EXPECT_NEAR(total, 1920695.7, 2.0);
  // docs/references.md 2.5 materials and the light's Ke.
  EXPECT_EQ(a.at("floor").material->rho, Color(0.7383f, 0.7360f, 0.7387f));
  EXPECT_EQ(a.at("left_wall_red").material->rho, Color(0.4939f, 0.0489f, 0.0512f));
  EXPECT_EQ(a.at("right_wall_green").material->rho, Color(0.0684f, 0.3985f, 0.0866f));
  EXPECT_EQ(a.at("light").material->emission, Color(20.7115f, 10.8551f, 2.7708f));
  EXPECT_EQ(a.at("light").material->rho, Color(0.78f));
  // The light faces down (-y), into the box.
  EXPECT_TRUE(a.at("light").areaByNormal.count(test::key(Vec3(0, -1, 0), 1e-3)));
  ASSERT_TRUE(builtin.camera);
  EXPECT_EQ(builtin.camera->eye, Vec3(278, 273, -800));
  EXPECT_NEAR(builtin.camera->fovDeg, 39.3077f, 1e-4);  // docs/references.md 2.2
  EXPECT_EQ(builtin.camera->width, 512);
  EXPECT_TRUE(builtin.lights.empty());
}

TEST(BuiltinScenes, CornellSpotHasNoEmittingSurfaceButASpot) {
  const Scene s = loadScene("cornell-spot");
  for (const Material& m : s.materials) EXPECT_FALSE(m.emits()) << m.name;
  ASSERT_EQ(s.lights.size(), 1u);
  const Light& l = s.lights[0];
  EXPECT_EQ(l.type, LightType::Spot);
  EXPECT_EQ(l.direction, Vec3(0, -1, 0));
  EXPECT_EQ(l.innerAngleDeg, 25.0f);
  EXPECT_EQ(l.outerAngleDeg, 35.0f);
  EXPECT_LT(l.position.y, 548.8f);  // below the ceiling
  EXPECT_TRUE(s.hasEmitters());
  EXPECT_NO_THROW(requireEmitters(s));
}

TEST(BuiltinScenes, RoomGrowsLinearlyAndIsDeterministic) {
  const Scene r1 = loadScene("room:1"), r8 = loadScene("room:8"), r16 = loadScene("room:16"),
              r32 = loadScene("room:32");
  EXPECT_LT(r1.triangles.size(), r8.triangles.size());
  EXPECT_LT(r8.triangles.size(), r16.triangles.size());
  const double ratio = double(r32.triangles.size()) / double(r16.triangles.size());
  EXPECT_GT(ratio, 1.8);
  EXPECT_LT(ratio, 2.2);
  EXPECT_TRUE(r1.hasEmitters());
  EXPECT_TRUE(r1.warnings.empty());
  const Scene again = loadScene("room:8");
  EXPECT_EQ(again.positions, r8.positions);
  const auto objects = test::summarize(r8, 1e-4);
  EXPECT_TRUE(objects.count("floor"));
  EXPECT_TRUE(objects.count("ceiling"));
  EXPECT_TRUE(objects.count("table_0"));
  EXPECT_TRUE(objects.count("shelf_2"));
  EXPECT_TRUE(objects.count("light_panel_7"));
  // Closed furniture boxes face out; the shell faces in.
  EXPECT_LT(objects.at("walls").volume + objects.at("floor").volume + objects.at("ceiling").volume,
            0.0);
  EXPECT_GT(objects.at("boxes_1").volume, 0.0);
}

TEST(BuiltinScenes, AtriumGrowsLinearlyAndIsClosedWithFacesTurnedIn) {
  const Scene a1 = loadScene("atrium:1"), a4 = loadScene("atrium:4"), a8 = loadScene("atrium:8");
  // Only the curved parts' tessellation grows: the increments per unit of N are equal.
  const double step1 = double(a4.triangles.size() - a1.triangles.size()) / 3.0;
  const double step2 = double(a8.triangles.size() - a4.triangles.size()) / 4.0;
  EXPECT_NEAR(step1, step2, 0.02 * step2);
  EXPECT_EQ(loadScene("atrium:4").positions, a4.positions);
  EXPECT_TRUE(a1.warnings.empty()) << a1.warnings.front();
  EXPECT_EQ(a1.lights.size(), 3u);
  for (const char* name : {"floor", "walls", "vault", "columns", "arches", "galleries", "railings"})
    EXPECT_TRUE(test::summarize(a1, 1e-4).count(name)) << name;
  // From the nave, in a spread of directions, every ray meets a surface from its front: the hall
  // is closed and every face a ray can reach faces the room.
  const RayCaster caster(a4);
  const Vec3 from(7.0f, 2.0f, 12.0f);
  int rays = 0;
  for (int i = 0; i < 60; ++i)
    for (int j = 0; j < 120; ++j, ++rays) {
      const float theta = 3.14159265f * (float(i) + 0.5f) / 60.0f;
      const float phi = 6.2831853f * (float(j) + 0.5f) / 120.0f;
      const Vec3 d(std::sin(theta) * std::cos(phi), std::cos(theta),
                   std::sin(theta) * std::sin(phi));
      const Hit hit = caster.intersect(Ray{from, d});
      ASSERT_TRUE(hit.valid()) << "ray " << rays;
      EXPECT_TRUE(hit.frontFace) << "ray " << rays << " met the back of triangle " << hit.triangle;
    }
}

// The textured atrium is the same hall: its floor a checker of tiles and its walls ashlar, whose
// means over the surface keep the untextured reflectances (what the per-object comparisons of the
// two rest on).
TEST(BuiltinScenes, TexturedAtriumShowsItsPatternAtTheSameMeanReflectance) {
  const Scene plain = loadScene("atrium:1"), textured = loadScene("atrium-textured:1");
  EXPECT_EQ(textured.positions, plain.positions);
  EXPECT_EQ(textured.triangles, plain.triangles);
  ASSERT_EQ(textured.texcoords.size(), textured.positions.size());
  EXPECT_TRUE(textured.warnings.empty()) << textured.warnings.front();
  // The floor's mean reflectance over a 1,000 x 1,000 grid of points, texel by texel, against the
  // plain floor's rho.
  uint32_t floorFace = 0;
  while (textured.objects[textured.faces[floorFace].object].name != "floor") ++floorFace;
  const Face& floor = textured.faces[floorFace];
  ASSERT_TRUE(textured.materials[floor.material].rhoTexture);
  Vec3d sum(0.0);
  const int n = 1000;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Vec3 p(14.0f * (float(i) + 0.5f) / n, 0.0f, 24.0f * (float(j) + 0.5f) / n);
      uint32_t triangle = 0;
      const Vec2 b = textured.locateOnFace(floorFace, p, triangle);
      sum += Vec3d(textured.reflectanceAt(triangle, b));
    }
  const Color mean = Color(sum / double(n * n));
  const Color expected = plain.materials[plain.faces[floorFace].material].rho;
  // applyTexture sets the factor to rho over the texture's mean, and the floor holds 7 x 12 whole
  // repeats of it: the grid's mean is rho up to its sampling of the tiles' edges.
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c], expected[c], 0.02f * expected[c]) << c;
  // The pattern: 0.5 m tiles, neighbours of the other tone (makeFloorTiles' tones have
  // luminances 0.93 and 0.68, 27% apart, the centres of two adjacent tiles more than a quarter).
  auto at = [&](float x, float z) {
    uint32_t triangle = 0;
    const Vec2 b = textured.locateOnFace(floorFace, Vec3(x, 0.0f, z), triangle);
    return luminance(textured.reflectanceAt(triangle, b));
  };
  const float a = at(5.25f, 9.25f), b = at(5.75f, 9.25f), c = at(5.25f, 9.75f);
  EXPECT_GT(std::abs(a - b), 0.25f * std::max(a, b));
  EXPECT_GT(std::abs(a - c), 0.25f * std::max(a, c));
  EXPECT_NEAR(at(5.25f, 9.25f), at(5.25f + 1.0f, 9.25f), 0.1f * a);  // the same tone a tile on
}

TEST(BuiltinScenes, NamesAndBadRoomDetail) {
  const std::vector<std::string> names = builtinSceneNames();
  EXPECT_NE(std::find(names.begin(), names.end(), "cornell"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "room:N"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "atrium:N"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "atrium-textured:N"), names.end());
  for (const char* bad : {"room:0", "room:-3", "room:abc", "room:", "atrium:0", "atrium:x"}) {
    const std::string m = test::errorOf([&] { loadScene(bad); });
    EXPECT_NE(m.find(bad), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace rad
