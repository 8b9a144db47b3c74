// The same small scene written as OBJ + MTL, .gltf (+ .bin) and .glb must load to the same
// triangles, materials and transforms. The data files in tests/data/scene/small were generated
// once by a script from one description: a 4 x 3 x 4 room facing inward, a 1 x 1 ceiling panel
// emitting Ke 10, a 0.8 m cube ("crate", rotated 30 degrees about y, at (1, 0.5, 1)) and an
// L-shaped prism ("bracket", mirrored by scale (-1, 1, 1), at (3, 0, 3)). The glTF files keep the
// transforms in nodes (matrix in .gltf; TRS with a parent node in .glb), the OBJ has them baked.
// The .glb uses uint8/uint32 indices and a strided POSITION view; both have a non-indexed mesh.

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <radiosity/scene_builder.h>
#include <radiosity/scene_loader.h>

#include <algorithm>
#include <filesystem>

#include "scene/io/obj_loader.h"
#include "scene_summary.h"

namespace rad {
namespace {

using test::kData;

// Reference values computed by hand from the description above.
constexpr double kRoomArea = 2 * 12 + 2 * 16 + 2 * 12;  // walls, floor+ceiling, ends
constexpr double kCrateArea = 6 * 0.8 * 0.8;
constexpr double kBracketArea = 2 * 0.51 + 4.0 * 0.5;  // L area 0.51, perimeter 4.0
constexpr double kCrateVolume = 0.8 * 0.8 * 0.8;
constexpr double kBracketVolume = 0.51 * 0.5;
constexpr double kRoomVolume = -(4.0 * 3.0 * 4.0);  // faces point inward

void expectSmallScene(const Scene& s) {
  const auto objects = test::summarize(s, 1e-4);
  ASSERT_EQ(objects.size(), 4u);
  EXPECT_NEAR(objects.at("room").area, kRoomArea, 1e-4);
  EXPECT_NEAR(objects.at("light").area, 1.0, 1e-5);
  EXPECT_NEAR(objects.at("crate").area, kCrateArea, 1e-5);
  EXPECT_NEAR(objects.at("bracket").area, kBracketArea, 1e-5);
  // Signed volumes prove the winding: outward for the crate and the mirrored bracket.
  EXPECT_NEAR(objects.at("room").volume, kRoomVolume, 1e-3);
  EXPECT_NEAR(objects.at("crate").volume, kCrateVolume, 1e-5);
  EXPECT_NEAR(objects.at("bracket").volume, kBracketVolume, 1e-5);
  // The crate's +x face turned 30 degrees about y: normal (cos 30, 0, -sin 30).
  EXPECT_NEAR(objects.at("crate").areaByNormal.at(test::key(Vec3(0.866025f, 0, -0.5f), 1e-3)), 0.64,
              1e-5);
  EXPECT_NEAR(objects.at("light").areaByNormal.at(test::key(Vec3(0, -1, 0), 1e-3)), 1.0, 1e-5);
  EXPECT_EQ(objects.at("crate").positions.size(), 8u);
  EXPECT_EQ(objects.at("bracket").positions.size(), 12u);
  EXPECT_TRUE(objects.at("crate").positions.count(
      test::key(Vec3(1.0f, 0.9f, 1.0f) +
                    Vec3(0.4f * 0.866025f + 0.4f * 0.5f, 0, -0.4f * 0.5f + 0.4f * 0.866025f),
                1e-4)));
  const Material& light = *objects.at("light").material;
  EXPECT_NEAR(light.emission.r, 10.0f, 1e-5);
  EXPECT_NEAR(light.rho.g, 0.5f, 1e-6);
  EXPECT_NEAR(objects.at("crate").material->rho.r, 0.7f, 1e-6);
  EXPECT_NEAR(objects.at("bracket").material->rho.b, 0.7f, 1e-6);
  EXPECT_TRUE(s.hasEmitters());
}

TEST(SceneFiles, ObjGltfAndGlbAgree) {
  const Scene obj = loadScene(kData + "small/small.obj");
  const Scene gltf = loadScene(kData + "small/small.gltf");
  const Scene glb = loadScene(kData + "small/small.glb");
  for (const Scene* s : {&obj, &gltf, &glb}) {
    SCOPED_TRACE(s->name);
    expectSmallScene(*s);
  }
  const auto a = test::summarize(obj, 1e-4), b = test::summarize(gltf, 1e-4),
             c = test::summarize(glb, 1e-4);
  for (const auto& [name, o] : a) {
    SCOPED_TRACE(name);
    EXPECT_EQ(o.positions, b.at(name).positions);
    EXPECT_EQ(o.positions, c.at(name).positions);
    for (const auto& [normal, area] : o.areaByNormal) {
      EXPECT_NEAR(area, b.at(name).areaByNormal.at(normal), 1e-5);
      EXPECT_NEAR(area, c.at(name).areaByNormal.at(normal), 1e-5);
    }
  }
  // doubleSided is a glTF notion; OBJ faces are one-sided.
  EXPECT_FALSE(a.at("bracket").material->twoSided);
  EXPECT_TRUE(b.at("bracket").material->twoSided);
  // The OBJ keeps the L-shaped polygon as one face of 4 triangles; the concave ear clipping
  // covers exactly its 0.51 area.
  size_t lFaces = 0;
  for (const Face& f : obj.faces) {
    if (f.corners.size() != 6) continue;
    ++lFaces;
    EXPECT_EQ(f.triangleCount, 4u);
    double sum = 0.0;
    for (uint32_t t = f.firstTriangle; t < f.firstTriangle + f.triangleCount; ++t)
      sum += obj.triangleArea(t);
    EXPECT_NEAR(sum, 0.51, 1e-6);
    EXPECT_NEAR(f.area, 0.51f, 1e-6);
  }
  EXPECT_EQ(lFaces, 2u);
}

TEST(SceneFiles, GltfSkipsNonTrianglePrimitivesWithOneWarning) {
  const Scene gltf = loadScene(kData + "small/small.gltf");
  size_t hits = 0;
  for (const std::string& w : gltf.warnings)
    hits += w.find("skipped 1 non-triangle") != std::string::npos;
  EXPECT_EQ(hits, 1u);
  // Shown after the scene's name, a warning names its file only when it is not the scene's own.
  for (const std::string& w : gltf.warnings)
    EXPECT_EQ(w.find("small.gltf"), std::string::npos) << w;
  const auto dir = test::scratchDir("warnings");
  const std::string json = test::writeFile(
      dir / "includes.json", R"({"geometry": [{"file": ")" + kData + R"(small/small.gltf"}]})");
  const Scene composed = loadScene(json);
  ASSERT_EQ(composed.warnings.size(), gltf.warnings.size());
  for (const std::string& w : composed.warnings)
    EXPECT_NE(w.find("small.gltf: "), std::string::npos) << w;
}

TEST(SceneFiles, JsonSceneComposesFilesLightsCameraSolver) {
  const Scene s = loadScene(kData + "small/scene.json");
  const Scene obj = loadScene(kData + "small/small.obj");
  const Scene glb = loadScene(kData + "small/small.glb");
  EXPECT_EQ(s.triangles.size(), obj.triangles.size() + glb.triangles.size());
  // The .glb part: scale 2, then 90 degrees about y ((x, z) -> (z, -x)), then +10 in x.
  const Bounds b = s.bounds();
  EXPECT_NEAR(b.min.x, 0.0f, 1e-4);
  EXPECT_NEAR(b.max.x, 18.0f, 1e-4);
  EXPECT_NEAR(b.min.z, -8.0f, 1e-4);
  EXPECT_NEAR(b.max.z, 4.0f, 1e-4);
  EXPECT_NEAR(b.max.y, 6.0f, 1e-4);
  double area = 0.0;
  for (uint32_t t = 0; t < s.triangles.size(); ++t) area += s.triangleArea(t);
  const double parts = kRoomArea + 1.0 + kCrateArea + kBracketArea;
  EXPECT_NEAR(area, parts * (1.0 + 4.0), 1e-3);
  // The override reaches the "red" material of both files.
  size_t red = 0;
  for (const Material& m : s.materials) {
    if (m.name != "red") continue;
    ++red;
    EXPECT_EQ(m.rho, Color(0.2f, 0.3f, 0.4f));
    EXPECT_TRUE(m.twoSided);
  }
  EXPECT_EQ(red, 2u);
  ASSERT_EQ(s.lights.size(), 3u);
  EXPECT_EQ(s.lights[0].type, LightType::Point);
  EXPECT_EQ(s.lights[1].type, LightType::Spot);
  EXPECT_EQ(s.lights[1].direction, Vec3(0, -1, 0));  // normalized from (0, -2, 0)
  EXPECT_EQ(s.lights[1].outerAngleDeg, 30.0f);
  EXPECT_EQ(s.lights[1].spinDegPerS, Vec3(0, 45, 0));
  ASSERT_EQ(s.lights[2].type, LightType::Ies);
  ASSERT_TRUE(s.lights[2].ies);
  // Default 1/179 W/sr per cd (Radiance WHTEFFICACY, docs/references.md 4.4) times the colour.
  EXPECT_NEAR(s.lights[2].intensity.g, 0.5 / 179.0, 1e-9);
  EXPECT_NEAR(s.lights[2].power().r, 20826.25 / 179.0, 1e-2);
  ASSERT_TRUE(s.camera);
  EXPECT_EQ(s.camera->width, 320);
  EXPECT_EQ(s.camera->fovDeg, 50.0f);
  EXPECT_EQ(s.solver.values.at("method"), SettingValue(std::string("voxel")));
  EXPECT_EQ(s.solver.values.at("spp"), SettingValue(int64_t(16)));
  EXPECT_EQ(s.solver.values.at("max_depth"), SettingValue(int64_t(5)));
  EXPECT_EQ(s.solver.values.at("seed"), SettingValue(int64_t(42)));
}

TEST(SceneFiles, ConcavePolygonTriangulationCoversItsArea) {
  // A U shape (8 corners, CCW about +y): 3 x 2 minus the 1 x 1.5 notch = 4.5 (shoelace).
  const auto dir = test::scratchDir("concave");
  const std::string path = test::writeFile(
      dir / "u.obj",
      "v 0 0 0\nv 0 0 -2\nv 3 0 -2\nv 3 0 0\nv 2 0 0\nv 2 0 -1.5\nv 1 0 -1.5\nv 1 0 0\n"
      "f 1 8 7 6 5 4 3 2\n");
  const Scene s = loadScene(path);
  double area = 0.0;
  for (uint32_t t = 0; t < s.triangles.size(); ++t) {
    area += s.triangleArea(t);
    EXPECT_NEAR(s.triangleNormal(t).y, 1.0f, 1e-6);
  }
  EXPECT_NEAR(area, 4.5, 1e-6);
  ASSERT_EQ(s.faces.size(), 1u);
  EXPECT_EQ(s.faces[0].triangleCount, 6u);
  EXPECT_EQ(s.objects.at(0).name, "u");  // unnamed: the file stem
}

TEST(SceneFiles, DegenerateTrianglesDroppedWithOneCountingWarning) {
  const auto dir = test::scratchDir("degenerate");
  const std::string path = test::writeFile(
      dir / "d.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 4\nf 1 2 3\nf 2 3 1\n");
  const Scene s = loadScene(path);
  EXPECT_EQ(s.triangles.size(), 1u);
  size_t hits = 0;
  for (const std::string& w : s.warnings)
    hits += w.find("dropped 2 degenerate") != std::string::npos;
  EXPECT_EQ(hits, 1u);
  // No MTL: the default grey material, announced once.
  EXPECT_EQ(s.materials.at(0).rho, Color(0.5f));
}

TEST(SceneFiles, ObjTransformAppliesAndMirroringKeepsFronts) {
  // x -> 5 - 2x: mirrors (negative determinant) and stretches; the crate's volume grows by 2
  // and stays positive only if the loader reverses the winding.
  glm::mat4 m(1.0f);
  m[0][0] = -2.0f;
  m[3] = glm::vec4(5.0f, 0.0f, 0.0f, 1.0f);
  SceneBuilder builder("mirrored");
  loadObj(builder, kData + "small/small.obj", m);
  const Scene s = builder.build();
  const auto objects = test::summarize(s, 1e-4);
  EXPECT_NEAR(objects.at("crate").volume, 2.0 * kCrateVolume, 1e-5);
  EXPECT_NEAR(objects.at("bracket").volume, 2.0 * kBracketVolume, 1e-5);
  EXPECT_NEAR(objects.at("room").volume, 2.0 * kRoomVolume, 1e-3);
  EXPECT_NEAR(s.bounds().min.x, -3.0f, 1e-5);
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

// The sample scenes the README's examples use load as they are meant to: the office with its
// three light groups, an animated light, a moving chair and a textured floor; the glTF room with
// its lamp, spot and cameras.
TEST(SampleScenes, TheReadmesScenesLoadWithTheirLightsAndCameras) {
  const std::string dir = std::string(RADIOSITY_SOURCE_DIR) + "/scenes/";
  const Scene office = loadScene(dir + "office.json");
  EXPECT_TRUE(office.warnings.empty());
  ASSERT_EQ(office.lights.size(), 3u);
  EXPECT_EQ(office.lights[0].group, "desk");
  EXPECT_EQ(office.lights[1].group, "ceiling");
  EXPECT_TRUE(office.lights[2].animated());
  ASSERT_EQ(office.dynamicObjects.size(), 1u);
  EXPECT_TRUE(office.hasEmitters());
  ASSERT_TRUE(office.camera);
  // Its floor is tiled by a texture, in metres.
  ASSERT_EQ(office.texcoords.size(), office.positions.size());
  const auto tiles = std::find_if(office.materials.begin(), office.materials.end(),
                                  [](const Material& m) { return m.name == "tiles"; });
  ASSERT_NE(tiles, office.materials.end());
  EXPECT_TRUE(tiles->rhoTexture);
  const Scene room = loadScene(dir + "lamp_room.gltf");
  EXPECT_EQ(room.lights.size(), 2u);
  ASSERT_EQ(room.cameras.size(), 2u);
  EXPECT_EQ(room.cameras[1].first, "corner");
}

// Every scene shipped, built in or in scenes/ (its files; the folders beside them hold their
// parts: meshes, textures, IES files), loads without a warning: a first run must not start with
// one.
TEST(SampleScenes, NoShippedSceneWarns) {
  std::vector<std::string> names;
  for (const std::string& name : builtinSceneNames()) {
    if (!name.ends_with(":N")) {
      names.push_back(name);
      continue;
    }
    const std::string family = name.substr(0, name.size() - 1);  // "room:"
    names.insert(names.end(), {family + "1", family + "3"});
  }
  const std::string dir = std::string(RADIOSITY_SOURCE_DIR) + "/scenes";
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string ext = entry.path().extension().string();
    if (ext == ".json" || ext == ".obj" || ext == ".gltf" || ext == ".glb")
      names.push_back(entry.path().string());
  }
  EXPECT_GE(names.size(), 8u + 2u);  // the built-ins and scenes/'s files
  for (const std::string& name : names) {
    const Scene scene = loadScene(name);
    EXPECT_TRUE(scene.warnings.empty()) << name << ": " << scene.warnings.front();
  }
}

// A scene's length unit: the built-ins know theirs, glTF is in metres by its specification, a
// scene file names its own ("unit"), an OBJ alone does not say.
TEST(SceneUnits, BuiltinsGltfAndSceneFilesKnowTheirUnit) {
  EXPECT_EQ(loadScene("cornell").unit.name, "mm");
  EXPECT_DOUBLE_EQ(loadScene("cornell-spot").unit.metres, 0.001);
  EXPECT_DOUBLE_EQ(loadScene("room:1").unit.metres, 1.0);
  EXPECT_DOUBLE_EQ(loadScene("atrium:1").unit.metres, 1.0);
  EXPECT_DOUBLE_EQ(loadScene(kData + "small/small.gltf").unit.metres, 1.0);
  EXPECT_DOUBLE_EQ(loadScene(kData + "small/small.glb").unit.metres, 1.0);
  const Scene obj = loadScene(kData + "small/small.obj");
  EXPECT_FALSE(obj.unit.known());
  EXPECT_EQ(obj.unit.symbol(), "scene unit");
  const auto dir = test::scratchDir("units");
  const std::string geometry = R"("geometry": [{"file": ")" + kData + R"(small/small.obj"}])";
  EXPECT_FALSE(loadScene(test::writeFile(dir / "none.json", "{" + geometry + "}")).unit.known());
  for (const auto& [name, metres] :
       {std::pair{"mm", 0.001}, {"cm", 0.01}, {"m", 1.0}, {"in", 0.0254}, {"ft", 0.3048}}) {
    const std::string file =
        test::writeFile(dir / "unit.json", fmt::format(R"({{"unit": "{}", {}}})", name, geometry));
    const Scene s = loadScene(file);
    EXPECT_EQ(s.unit.name, name);
    EXPECT_DOUBLE_EQ(s.unit.metres, metres) << name;
  }
}

}  // namespace
}  // namespace rad
