// Files built to break a loader (found by mutating our test data, see the hardening issue):
// offsets that wrap, nesting that overflows a stack, counts that ask for terabytes, graphs
// that multiply, magnitudes beyond a float. Each one must end in an InputError naming the file
// and what was wrong, quickly and without a large allocation.

#include <gtest/gtest.h>
#include <radiosity/ies_profile.h>
#include <radiosity/scene_loader.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>

#include "core/address_space_limit.h"
#include "scene_summary.h"

namespace rad {
namespace {

using test::errorOf;
using test::kData;
using Json = nlohmann::json;

void expectMessage(const std::string& message, std::initializer_list<const char*> parts) {
  for (const char* p : parts) EXPECT_NE(message.find(p), std::string::npos) << message;
}

class HostileInput : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::scratchDir("hostile");
    for (const char* f : {"small.gltf", "small.bin", "small.obj", "small.mtl"})
      std::filesystem::copy_file(kData + "small/" + f, dir_ / f);
    std::ifstream in(dir_ / "small.gltf");
    gltf_ = Json::parse(in);
  }
  /// Loads the test glTF after `edit` changed it; the InputError message, or "(no error)".
  std::string gltfError(const std::function<void(Json&)>& edit) {
    Json g = gltf_;
    edit(g);
    const std::string path = test::writeFile(dir_ / "edited.gltf", g.dump());
    return errorOf([&] { loadScene(path); });
  }
  std::string sceneError(const std::string& name, const std::string& text) {
    const std::string path = test::writeFile(dir_ / name, text);
    return errorOf([&] { loadScene(path); });
  }
  std::filesystem::path dir_;
  Json gltf_;
};

TEST_F(HostileInput, GltfOffsetsAndCountsThatWrapAreRefused) {
  // Before: the bounds check wrapped and the reader read outside the buffer (exit 0).
  expectMessage(gltfError([](Json& g) { g["accessors"][0]["byteOffset"] = UINT64_MAX - 7; }),
                {"edited.gltf", "/attributes/POSITION", "runs past the end"});
  expectMessage(gltfError([](Json& g) { g["bufferViews"][0]["byteOffset"] = UINT64_MAX - 15; }),
                {"edited.gltf", "runs past the end"});
  // A count near 2^62 asked for a vector of 2^62 elements (exit 1, "max_size").
  expectMessage(gltfError([](Json& g) { g["accessors"][0]["count"] = uint64_t(1) << 62; }),
                {"edited.gltf", "4611686018427387904 elements", "runs past the end"});
  // A stride shorter than the element would read overlapping, meaningless positions.
  expectMessage(gltfError([](Json& g) { g["bufferViews"][0]["byteStride"] = 4; }),
                {"edited.gltf", "byteStride 4 is smaller than an element (12 bytes)"});
  EXPECT_EQ(gltfError([](Json&) {}), "(no error)");
}

TEST_F(HostileInput, DeepNestingIsRefusedBeforeAnyParserRecurses) {
  // Before: 20,000 nested arrays in a glTF's extras, or 100,000 in a scene file's value,
  // overflowed the stack (SIGSEGV).
  const std::string deep = std::string(20000, '[') + std::string(20000, ']');
  std::string gltf = gltf_.dump();
  gltf.insert(gltf.find('{') + 1, "\"extras\": " + deep + ", ");
  test::writeFile(dir_ / "deep.gltf", gltf);
  expectMessage(errorOf([&] { loadScene((dir_ / "deep.gltf").string()); }),
                {"deep.gltf", "nested deeper than 512 levels"});
  const std::string deeper = std::string(100000, '[') + std::string(100000, ']');
  expectMessage(sceneError("deep.json",
                           "{\"geometry\": [{\"file\": \"small.obj\"}],\n"
                           "\"camera\": {\"eye\": " +
                               deeper + "}}"),
                {"deep.json:2:", "nested deeper than 512 levels"});
  // Nesting a few levels deep, with brackets inside strings, is fine.
  EXPECT_EQ(sceneError("strings.json",
                       "{\"geometry\": [{\"file\": \"small.obj\"}], "
                       "\"lights\": [{\"type\": \"point\", \"group\": \"[[[{{\","
                       " \"position\": [1, 1, 1], \"intensity\": [1, 1, 1]}]}"),
            "(no error)");
}

TEST_F(HostileInput, CoordinatesBeyondTheFloatsResolutionAreRefused) {
  // Before: a scale of 1e18 loaded and then aborted inside Embree (exit 134).
  expectMessage(sceneError("huge.json", R"({"geometry": [{"file": "small.obj",
                                           "transform": {"scale": 1e18}}]})"),
                {"small.obj:", "beyond 1e+09 scene units", "check the scale"});
  expectMessage(sceneError("light.json", R"({"geometry": [{"file": "small.obj"}], "lights": [
                           {"type": "point", "position": [0, 1e30, 0], "intensity": [1, 1, 1]}]})"),
                {"light.json: /lights/0/position", "beyond 1e+09"});
  expectMessage(sceneError("eye.json", R"({"geometry": [{"file": "small.obj"}],
                           "camera": {"eye": [1e39, 0, 0]}})"),
                {"/camera/eye/0", "32-bit float range"});
  // A building in millimetres (1e5) is an ordinary scene.
  EXPECT_EQ(sceneError("mm.json", R"({"geometry": [{"file": "small.obj",
                                     "transform": {"scale": 1e4}}]})"),
            "(no error)");
}

TEST_F(HostileInput, ObjFacesOfMoreThan255CornersAreRefusedNotMangled) {
  // Before: tinyobjloader kept the corner count in one byte, so a 260-corner disk loaded as 3
  // triangles. At 255 corners the disk loads whole: the area of a regular 255-gon of radius 1.
  auto disk = [&](int corners) {
    std::ostringstream text;
    for (int i = 0; i < corners; ++i) {
      const double a = 2.0 * std::numbers::pi * i / corners;
      text << "v " << std::cos(a) << " 0 " << -std::sin(a) << "\n";
    }
    text << "f";
    for (int i = 1; i <= corners; ++i) text << ' ' << i;
    text << "\n";
    return test::writeFile(dir_ / ("disk" + std::to_string(corners) + ".obj"), text.str());
  };
  expectMessage(errorOf([&] { loadScene(disk(260)); }),
                {"disk260.obj:261", "260 corners, at most 255"});
  const Scene s = loadScene(disk(255));
  double area = 0.0;
  for (uint32_t t = 0; t < s.triangles.size(); ++t) area += s.triangleArea(t);
  EXPECT_NEAR(area, 0.5 * 255 * std::sin(2.0 * std::numbers::pi / 255), 1e-5);
}

TEST_F(HostileInput, GltfNodeGraphsMustBeTrees) {
  // Before: node i listing node i+1 twice, 40 levels deep, visited 2^40 leaves (a hang, or out
  // of memory with a mesh on the leaf). A cycle, and a node under two parents, are refused.
  expectMessage(gltfError([](Json& g) {
                  const size_t first = g["nodes"].size();
                  for (size_t i = 0; i < 40; ++i)
                    g["nodes"].push_back({{"children", {first + i + 1, first + i + 1}}});
                  g["nodes"].push_back({{"mesh", 0}});
                  g["scenes"][0]["nodes"] = {first};
                }),
                {"edited.gltf: /nodes/", "reached twice", "strict trees"});
  expectMessage(gltfError([](Json& g) { g["nodes"][0]["children"] = {0}; }),
                {"/nodes/0", "reached twice"});
  expectMessage(gltfError([](Json& g) {
                  g["scenes"][0]["nodes"] = {0, 1, 1};
                }),
                {"/nodes/1", "reached twice"});
}

TEST_F(HostileInput, NumbersBeyondRangeGetExitTwoNamingTheFile) {
  // A number that overflows a double (before: exit 1 with the JSON library's message).
  expectMessage(sceneError("big.json", R"({"geometry": [{"file": "small.obj"}],
                                         "camera": {"fov_deg": 1e400}})"),
                {"big.json", "number overflow", "1e400"});
  // Ke 1e39 is finite as a double and infinite as a float (before: emitted inf, exit 0).
  std::ofstream(dir_ / "small.mtl", std::ios::app) << "newmtl hot\nKd 0.5 0.5 0.5\nKe 1e39 1 1\n";
  expectMessage(errorOf([&] { loadScene((dir_ / "small.obj").string()); }),
                {"small.mtl:", "'1e39'", "32-bit float"});
  // The same through glTF's emissive strength.
  expectMessage(
      gltfError([](Json& g) {
        g["materials"][0]["emissiveFactor"] = {1, 1, 1};
        g["materials"][0]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] =
            1e39;
      }),
      {"edited.gltf", "emission", "must be finite"});
}

TEST_F(HostileInput, CountsAskingForMoreThanTheFileHoldsAllocateNothing) {
  // An IES file whose angle counts (100000 x 100000) asked for 80 GB of candela values
  // (before: out of memory). Under a 64 MB address-space margin it must fail by its message.
  std::string text = "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 100000 100000 1 1 0.1 0.1 0\n1 1 100\n";
  for (int i = 0; i < 100000; ++i) text += std::to_string(i * 0.0009) + "\n";  // %f: 6 decimals
  for (int i = 0; i < 100000; ++i) text += std::to_string(i * 0.0036) + "\n";
  const std::string ies = test::writeFile(dir_ / "huge.ies", text + "1 2 3 4\n");
  test::AddressSpaceLimit limit(64 << 20);
  if (!limit.lowered()) GTEST_SKIP() << "cannot lower the address-space limit here";
  expectMessage(errorOf([&] { loadIesProfile(ies); }),
                {"huge.ies:", "expected 10000000000 candela values (100000 x 100000), found 4"});
}

// Found by fuzzing: a vertical angle of 950 degrees (and horizontal ones of 15000) parsed, and
// the profile's flux came out negative. Angles must lie in their photometric type's range.
TEST_F(HostileInput, IesAnglesOutsideTheirTypesRangeAreRefused) {
  auto profile = [&](int type, const std::string& angles) {
    std::ostringstream text;
    text << "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1.0 2 2 " << type << " 1 0.3 0.4 0\n1 1 100\n"
         << angles << "1 2 3 4\n";
    return test::writeFile(dir_ / "angles.ies", text.str());
  };
  expectMessage(errorOf([&] { loadIesProfile(profile(1, "0 950\n0 90\n")); }),
                {"angles.ies:", "vertical angles must lie in [0, 180]", "950"});
  expectMessage(errorOf([&] { loadIesProfile(profile(1, "0 90\n0 15000\n")); }),
                {"horizontal angles must lie in [0, 360]", "15000"});
  expectMessage(errorOf([&] { loadIesProfile(profile(3, "-90 120\n0 90\n")); }),
                {"vertical angles must lie in [-90, 90]"});
  EXPECT_EQ(errorOf([&] { loadIesProfile(profile(1, "0 180\n0 360\n")); }), "(no error)");
}

TEST_F(HostileInput, DevicesAreReadNoFurtherThanTheLimit) {
  // `mtllib /dev/zero` read until memory ran out; now the read stops at the MTL limit.
  const std::string obj =
      test::writeFile(dir_ / "zero.obj", "mtllib /dev/zero\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  expectMessage(errorOf([&] { loadScene(obj); }), {"/dev/zero", "larger than 256 MiB"});
}

TEST_F(HostileInput, MessagesEchoATokenShortAndPrintable) {
  // Before: a 300 KB string with control characters was echoed whole into the message.
  std::string name;
  for (int i = 0; i < 50000; ++i) name += "\\u0007\\u001b[31mx";
  const std::string message = sceneError("token.json",
                                         "{\"geometry\": [{\"file\": \"small.obj\"}],"
                                         " \"lights\": [{\"type\": \"" +
                                             name + "\"}]}");
  expectMessage(message, {"token.json: /lights/0/type", "unknown light type", "\\x07\\x1b[31mx"});
  EXPECT_LT(message.size(), 400u) << message;
  for (const char c : message) EXPECT_FALSE(static_cast<unsigned char>(c) < 0x20) << message;
  // Keys too: a 100 KB unknown key is cut in the JSON pointer.
  const std::string key(100000, 'k');
  const std::string keyMessage = sceneError("key.json", "{\"" + key + "\": 1}");
  expectMessage(keyMessage, {"key.json: /kkk", "unknown key (expected one of"});
  EXPECT_LT(keyMessage.size(), 1000u);
}

}  // namespace
}  // namespace rad
