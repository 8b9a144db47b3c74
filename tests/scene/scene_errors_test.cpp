// Every kind of bad scene input throws InputError naming the file and the line or JSON path.

#include <gtest/gtest.h>
#include <radiosity/scene_loader.h>
#include <radiosity/solver_settings.h>

#include "scene_summary.h"

namespace rad {
namespace {

using test::errorOf;
using test::kData;

void expectMessage(const std::string& message, std::initializer_list<const char*> parts) {
  for (const char* p : parts) EXPECT_NE(message.find(p), std::string::npos) << message;
}

TEST(SceneErrors, MissingFileAndUnsupportedExtension) {
  expectMessage(errorOf([] { loadScene("/nonexistent/room.obj"); }), {"room.obj", "cannot open"});
  expectMessage(errorOf([] { loadScene("/nonexistent/room.json"); }), {"room.json", "cannot open"});
  expectMessage(errorOf([] { loadScene("nowhere"); }), {"nowhere", "cannot open"});
  const auto dir = test::scratchDir("ext");
  const std::string ply = test::writeFile(dir / "mesh.ply", "ply\n");
  expectMessage(errorOf([&] { loadScene(ply); }), {"mesh.ply", "'.ply'", ".json", ".glb"});
  // A directory, even one named like a scene file, is not read as one.
  expectMessage(errorOf([&] { loadScene(dir.string()); }), {"is a directory", ".gltf"});
  std::filesystem::create_directories(dir / "folder.obj");
  expectMessage(errorOf([&] { loadScene((dir / "folder.obj").string()); }),
                {"folder.obj", "is a directory"});
  // Upper-case extensions are accepted.
  const std::string upper =
      test::writeFile(dir / "TRI.OBJ", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_EQ(loadScene(upper).triangles.size(), 1u);
}

TEST(SceneErrors, MalformedObjLines) {
  const auto dir = test::scratchDir("obj");
  struct Case {
    const char* text;
    const char* line;
    const char* what;
  };
  const Case cases[] = {
      {"v 0 0 0\nv 1 abc 0\n", "bad.obj:2", "abc"},
      {"v 0 0\n", "bad.obj:1", "3 finite coordinates"},
      {"v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n", "bad.obj:3", "not finite"},
      {"v 0 0 0\nv 1 0 0\nv 0 inf 0\nf 1 2 3\n", "bad.obj:3", "not finite"},
      {"# c\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "bad.obj:5", "out of range"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", "bad.obj:4", "index 0"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", "bad.obj:4", "not an integer"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "bad.obj:4", "at least 3"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//2 2//1 3//1\n", "bad.obj:4", "normal index"},
      {"vn 0 1\n", "bad.obj:1", "normal"},
      {"vt x\n", "bad.obj:1", "'x'"},
  };
  for (const Case& c : cases) {
    const std::string path = test::writeFile(dir / "bad.obj", c.text);
    expectMessage(errorOf([&] { loadScene(path); }), {c.line, c.what});
  }
  // A missing MTL library names the library.
  const std::string noMtl = test::writeFile(dir / "nomtl.obj", "mtllib gone.mtl\nv 0 0 0\n");
  expectMessage(errorOf([&] { loadScene(noMtl); }), {"gone.mtl", "cannot open"});
}

TEST(SceneErrors, MalformedMtlStatements) {
  const auto dir = test::scratchDir("mtl");
  test::writeFile(dir / "m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
  const std::string obj = (dir / "m.obj").string();
  struct Case {
    const char* text;
    const char* line;
    const char* what;
  };
  const Case cases[] = {
      {"newmtl a\nKd 0.5 abc 0.5\n", "m.mtl:2", "abc"},
      {"newmtl a\n\nKd 1.5 0.5 0.5\n", "m.mtl:3", "must be in [0, 1]"},
      {"newmtl a\nKd 0.5 -0.1 0.5\n", "m.mtl:2", "must be in [0, 1]"},
      {"newmtl a\nKe -1 0 0\n", "m.mtl:2", ">= 0"},
      {"newmtl a\nKd 0.5 0.5\n", "m.mtl:2", "1 or 3"},
      {"newmtl a\nNs x\n", "m.mtl:2", "'x'"},
  };
  for (const Case& c : cases) {
    test::writeFile(dir / "m.mtl", c.text);
    expectMessage(errorOf([&] { loadScene(obj); }), {c.line, c.what});
  }
  test::writeFile(dir / "m.mtl", "newmtl a\nKd 0.25 0.5 0.75\nKe 1 2 3\n");
  const Scene s = loadScene(obj);
  EXPECT_EQ(s.materials.at(0).rho, Color(0.25f, 0.5f, 0.75f));
  EXPECT_EQ(s.materials.at(0).emission, Color(1, 2, 3));
}

TEST(SceneErrors, BrokenGltfAndGlb) {
  expectMessage(errorOf([] { loadScene(kData + "small/broken.gltf"); }), {"broken.gltf"});
  expectMessage(errorOf([] { loadScene(kData + "small/truncated.glb"); }), {"truncated.glb"});
  expectMessage(errorOf([] { loadScene(kData + "small/missing_buffer.gltf"); }),
                {"missing_buffer.gltf", "does_not_exist.bin"});
  const auto dir = test::scratchDir("gltf");
  const std::string notGlb = test::writeFile(dir / "text.glb", "this is not a glb file");
  expectMessage(errorOf([&] { loadScene(notGlb); }), {"text.glb"});
}

TEST(SceneErrors, GltfBaseColorOneIsClampedWithAWarning) {
  const auto dir = test::scratchDir("gltf_clamp");
  // One triangle; the buffer is 3 float positions, base64 in a data URI.
  const std::string gltf = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
    "nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0},"material":0}]}],
    "materials":[{"name":"paper","pbrMetallicRoughness":{"baseColorFactor":[1,1,1,1]}}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",
                  "min":[0,0,0],"max":[1,1,0]}],
    "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36}],
    "buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]})";
  const Scene s = loadScene(test::writeFile(dir / "paper.gltf", gltf));
  ASSERT_EQ(s.triangles.size(), 1u);
  EXPECT_NEAR(s.materials.at(0).rho.r, 0.999f, 1e-6);
  EXPECT_EQ(s.objects.at(0).name, "node0");
  size_t hits = 0;
  for (const std::string& w : s.warnings)
    hits += w.find("1 material of reflectance 1 taken as 0.999") != std::string::npos;
  EXPECT_EQ(hits, 1u);
}

// OBJ's Kd 1 is taken as glTF's baseColorFactor 1 is: 0.999, with one warning that counts them.
TEST(SceneErrors, ObjKdOneIsClampedAsGltfsIs) {
  const auto dir = test::scratchDir("obj_clamp");
  test::writeFile(dir / "white.mtl",
                  "newmtl paper\nKd 1 1 1\nnewmtl chalk\nKd 1 0.9 0.9\n"
                  "newmtl grey\nKd 0.5 0.5 0.5\n");
  const Scene s = loadScene(
      test::writeFile(dir / "white.obj",
                      "mtllib white.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                      "usemtl paper\nf 1 2 3\nusemtl chalk\nf 2 4 3\nusemtl grey\nf 1 3 4\n"));
  size_t clamped = 0, warned = 0;
  for (const Material& m : s.materials) clamped += maxComponent(m.rho) == 0.999f;
  for (const std::string& w : s.warnings)
    warned += w.find("2 materials of reflectance 1 taken as 0.999") != std::string::npos;
  EXPECT_EQ(clamped, 2u);
  EXPECT_EQ(warned, 1u);
}

class JsonErrors : public testing::Test {
 protected:
  std::string load(const std::string& text) {
    const auto dir = test::scratchDir("json");
    const std::string path = test::writeFile(dir / "scene.json", text);
    return errorOf([&] { loadScene(path); });
  }
  const std::string obj_ = "\"" + kData + "small/small.obj\"";
  // The error of a scene whose "solver" object is `solver`: the loader keeps its values, and
  // resolving them against the methods' settings table judges them.
  std::string resolve(const std::string& solver) {
    const auto dir = test::scratchDir("json");
    const std::string path =
        test::writeFile(dir / "scene.json",
                        "{\"geometry\": [{\"file\": " + obj_ + "}], \"solver\": " + solver + "}");
    return errorOf([&] {
      const Scene scene = loadScene(path);
      resolveMethodSettings(scene.solver, {}, scene.name);
    });
  }
  std::string withLight(const std::string& light) {
    return "{\"geometry\": [{\"file\": " + obj_ + "}], \"lights\": [" + light + "]}";
  }
};

TEST_F(JsonErrors, ParseErrorNamesLineAndColumn) {
  // The stray comma is on line 3, column 12 (after two blanks, "camera" and the colon).
  expectMessage(load("{\n  \"lights\": [],\n  \"camera\":,\n}\n"),
                {"scene.json:3:", "invalid JSON"});
  expectMessage(load("{\n  \"lights\": [],\n  \"camera\":,\n}\n"), {"scene.json:3:12"});
  expectMessage(load("{ \"geometry\": ["), {"scene.json:1:"});
}

TEST_F(JsonErrors, UnknownKeysNameTheirPath) {
  expectMessage(load("{\"lihgts\": []}"), {"scene.json: /lihgts", "unknown key", "lights"});
  expectMessage(load(withLight(R"({"type": "point", "position": [0,1,0], "intenisty": [1,1,1]})")),
                {"scene.json: /lights/0/intenisty", "unknown key", "intensity"});
  expectMessage(load("{\"camera\": {\"fov\": 40}}"), {"/camera/fov", "fov_deg"});
  expectMessage(load("{\"geometry\": [{\"file\": " + obj_ + ", \"transfrom\": {}}]}"),
                {"/geometry/0/transfrom"});
  expectMessage(resolve("{\"metod\": \"patch\"}"), {"/solver/metod"});
}

TEST_F(JsonErrors, UnitIsOneOfTheKnownNames) {
  expectMessage(load(R"({"unit": "furlong"})"),
                {"scene.json: /unit", "unknown unit 'furlong'", "mm, cm, m, in, ft"});
  expectMessage(load(R"({"unit": 0.001})"), {"scene.json: /unit", "expected a string"});
}

TEST_F(JsonErrors, LightPathsNameTheirKeyframe) {
  const std::string spot = R"({"type": "spot", "position": [0,1,0], "direction": [0,-1,0],
      "intensity": [1,1,1], "inner_angle_deg": 10, "outer_angle_deg": 20, "path": )";
  expectMessage(load(withLight(spot + "[]}")), {"/lights/0/path", "non-empty array"});
  expectMessage(
      load(withLight(spot + R"([{"t": 1, "position": [0,1,0]}, {"t": 1, "position": [1,1,0]}]})")),
      {"/lights/0/path/1/t", "greater than the previous"});
  expectMessage(load(withLight(spot + R"([{"position": [0,1,0]}]})")),
                {"/lights/0/path/0", "\"t\""});
  expectMessage(load(withLight(spot + R"([{"t": 0}]})")), {"/lights/0/path/0", "sets nothing"});
  expectMessage(load(withLight(spot + R"([{"t": 0, "direction": [0,0,0]}]})")),
                {"/lights/0/path/0/direction", "zero length"});
  expectMessage(load(withLight(R"({"type": "point", "position": [0,1,0], "intensity": [1,1,1],
      "path": [{"t": 0, "direction": [0,-1,0]}]})")),
                {"/lights/0/path/0/direction", "unknown key"});
}

TEST_F(JsonErrors, LightGroupNamesAreNonEmptyTextWithoutTheFlagsSeparators) {
  const std::string point =
      R"({"type": "point", "position": [0,1,0], "intensity": [1,1,1], "group": )";
  expectMessage(load(withLight(point + "3}")), {"/lights/0/group", "string"});
  expectMessage(load(withLight(point + "\"\"}")), {"/lights/0/group", "non-empty"});
  expectMessage(load(withLight(point + "\"a=b\"}")), {"/lights/0/group", "'='"});
}

TEST_F(JsonErrors, DynamicObjectsNameTheirField) {
  expectMessage(load("{\"dynamic_objects\": {}}"), {"/dynamic_objects", "expected an array"});
  expectMessage(load("{\"dynamic_objects\": [{\"name\": \"ball\"}]}"),
                {"/dynamic_objects/0", "missing key \"file\""});
  expectMessage(load("{\"dynamic_objects\": [{\"file\": " + obj_ + ", \"speed\": 1}]}"),
                {"/dynamic_objects/0/speed", "unknown key"});
  expectMessage(load("{\"dynamic_objects\": [{\"file\": " + obj_ +
                     ", \"path\": [{\"t\": 1, \"position\": [0,0,0]}, {\"t\": 0, "
                     "\"position\": [1,0,0]}]}]}"),
                {"/dynamic_objects/0/path/1/t", "greater than the previous"});
  expectMessage(load("{\"dynamic_objects\": [{\"file\": " + obj_ + ", \"rho\": [2,0,0]}]}"),
                {"/dynamic_objects/0/rho"});
}

TEST_F(JsonErrors, WrongTypesAndRanges) {
  expectMessage(load("{\"camera\": {\"fov_deg\": \"wide\"}}"),
                {"/camera/fov_deg", "expected a number"});
  expectMessage(load("{\"camera\": {\"fov_deg\": 180}}"), {"/camera/fov_deg", "(0, 180)"});
  expectMessage(load("{\"camera\": {\"fov_deg\": 0}}"), {"/camera/fov_deg", "(0, 180)"});
  expectMessage(load("{\"camera\": {\"width\": 0}}"), {"/camera/width", "out of range"});
  expectMessage(load("{\"camera\": {\"height\": 2.5}}"), {"/camera/height", "integer"});
  expectMessage(load("{\"geometry\": {}}"), {"/geometry", "expected an array"});
  expectMessage(load(withLight(R"({"type": "point", "position": [0,1], "intensity": [1,1,1]})")),
                {"/lights/0/position", "3 numbers"});
  expectMessage(load(withLight(R"({"type": "point", "position": [0,1,0], "intensity": [1,-1,1]})")),
                {"/lights/0/intensity", ">= 0"});
  // Beyond kMaxLight: more light than a solve's products hold in floats.
  expectMessage(
      load(withLight(R"({"type": "point", "position": [0,1,0], "intensity": [1e19,1,1]})")),
      {"/lights/0/intensity", "must be below 1e+18"});
  expectMessage(load(withLight(R"({"type": "spot", "position": [0,1,0], "direction": [0,0,0],
                    "intensity": [1,1,1], "inner_angle_deg": 10, "outer_angle_deg": 20})")),
                {"/lights/0/direction", "zero length"});
  expectMessage(load(withLight(R"({"type": "spot", "position": [0,1,0], "direction": [0,-1,0],
                    "intensity": [1,1,1], "inner_angle_deg": 30, "outer_angle_deg": 20})")),
                {"/lights/0", "inner <= outer"});
  expectMessage(load(withLight(R"({"type": "laser", "position": [0,1,0]})")),
                {"/lights/0/type", "laser"});
  expectMessage(resolve("{\"method\": \"magic\"}"), {"/solver/method", "patch, voxel"});
  expectMessage(resolve("{\"spp\": 0}"), {"/solver/spp", "out of range"});
  // The patch method's choices are checked against the names the library spells them by.
  expectMessage(resolve("{\"solver\": \"gauss\"}"),
                {"/solver/solver", "'gauss'", "gauss-seidel, jacobi, progressive"});
  expectMessage(resolve("{\"ff_estimator\": \"rays\"}"),
                {"/solver/ff_estimator", "hemisphere, pairwise, exact"});
  expectMessage(resolve("{\"shading\": \"gouraud\"}"), {"/solver/shading", "smooth, flat"});
  expectMessage(load("{\"geometry\": [{\"file\": \"missing.obj\"}]}"),
                {"missing.obj", "cannot open"});
  expectMessage(load("{\"geometry\": [{\"file\": \"a.stl\"}]}"), {"/geometry/0/file", "'.stl'"});
  expectMessage(load(withLight(R"({"type": "ies", "file": "none.ies", "position": [0,1,0]})")),
                {"none.ies", "cannot open"});
}

TEST_F(JsonErrors, MaterialOverridesAreChecked) {
  auto scene = [&](const std::string& material) {
    return "{\"geometry\": [{\"file\": " + obj_ + "}], \"materials\": {" + material + "}}";
  };
  expectMessage(load(scene(R"("red": {"rho": [1.0, 0.5, 0.5]})")),
                {"/materials/red/rho", "[0, 1)"});
  expectMessage(load(scene(R"("red": {"rho": [0.5, -0.1, 0.5]})")),
                {"/materials/red/rho", "[0, 1)"});
  expectMessage(load(scene(R"("red": {"two_sided": 1})")),
                {"/materials/red/two_sided", "true or false"});
  expectMessage(load(scene(R"("purple": {"rho": [0.5, 0.5, 0.5]})")), {"/materials/purple", "red"});
}

// A geometry entry's "material" gives all its faces one material: one of the files' by name, or
// one the "materials" object defines (a file without materials, or a second copy repainted).
TEST_F(JsonErrors, GeometryEntriesAssignMaterials) {
  const auto dir = test::scratchDir("assign");
  const std::string path = test::writeFile(
      dir / "scene.json",
      "{\"geometry\": [{\"file\": " + obj_ + "}, {\"file\": " + obj_ +
          ", \"material\": \"marble\", \"transform\": "
          "{\"translate\": [10, 0, 0]}}], \"materials\": {\"marble\": {\"rho\": [0.8, 0.78, 0.75],"
          " \"two_sided\": true}}}");
  const Scene s = loadScene(path);
  ASSERT_EQ(s.faces.size() % 2, 0u);
  const size_t half = s.faces.size() / 2;
  for (size_t f = 0; f < s.faces.size(); ++f) {
    const Material& m = s.materials[s.faces[f].material];
    if (f < half) {
      EXPECT_NE(m.name, "marble") << "face " << f;
    } else {
      EXPECT_EQ(m.name, "marble") << "face " << f;
      EXPECT_EQ(m.rho, Color(0.8f, 0.78f, 0.75f));
      EXPECT_TRUE(m.twoSided);
    }
  }
  expectMessage(load("{\"geometry\": [{\"file\": " + obj_ + ", \"material\": \"onyx\"}]}"),
                {"/geometry/0/material", "no material named 'onyx'"});
}

TEST(SceneErrors, RequireEmittersRejectsADarkScene) {
  const auto dir = test::scratchDir("dark");
  const std::string path =
      test::writeFile(dir / "dark.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const Scene s = loadScene(path);
  expectMessage(errorOf([&] { requireEmitters(s); }),
                {"dark.obj", "no emitting surface and no light"});
  EXPECT_NO_THROW(requireEmitters(loadScene("cornell")));
}

}  // namespace
}  // namespace rad
