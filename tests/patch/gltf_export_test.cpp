// The lit patch mesh as binary glTF: read back with tinygltf, it must be the patch mesh (triangle
// count, area, one node per object), carry the radiance the renderer shows as vertex colours, and
// be written atomically like every other output.
#include <gtest/gtest.h>
#include <radiosity/gltf_export.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/scene_loader.h>
#include <radiosity/texture.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <glm/gtc/constants.hpp>
#include <limits>
#include <span>

#include "output/glb_reader.h"
#include "patch_test_scenes.h"

namespace fs = std::filesystem;

namespace rad {
namespace {

using test::loadGlb;
using test::readAccessor;

// The lit cube room, its lamp's radiance above 1 so that its colours clamp.
Scene litRoom() {
  return test::litCubeRoom(Color(0.3f), Color(1.5f));
}

// litRoom() solved with the default settings but the patch size.
struct SolvedRoom {
  static PatchRadiositySettings withPatchSize(float patchSize) {
    PatchRadiositySettings s;
    s.patchSize = patchSize;
    return s;
  }
  explicit SolvedRoom(float patchSize)
      : settings(withPatchSize(patchSize)), solution(scene, settings) {}

  const Scene scene = litRoom();
  const PatchRadiositySettings settings;
  const PatchRadiosity solution;
};

fs::path freshDir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::vector<std::string> filesIn(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir))
    names.push_back(entry.path().filename().string());
  return names;
}

TEST(PatchGlbExport, IsTheLitPatchMesh) {
  const SolvedRoom room(0.125f);
  const Scene& scene = room.scene;
  const PatchRadiositySettings& settings = room.settings;
  const PatchRadiosity& solution = room.solution;
  const fs::path dir = freshDir("radiosity_glb_export");
  const fs::path file = dir / "room.glb";
  solution.exportGlb(file.string());
  // The temporary was renamed, not left beside it.
  EXPECT_EQ(filesIn(dir), std::vector<std::string>{"room.glb"});
  const tinygltf::Model model = loadGlb(file);

  // The same mesh the solver built, the two-sided wall's mirrored back patches included (with
  // their own light), a quad patch being 2 triangles.
  const PatchMesh mesh(scene, {settings.patchSize, settings.targetPatches});
  size_t expectedTriangles = 0;
  for (uint32_t p = 0; p < mesh.size(); ++p) expectedTriangles += mesh.nodeOf(p).cornerCount() - 2;
  double sceneArea = 0.0;  // both sides of the two-sided faces
  for (const Face& f : scene.faces)
    sceneArea += (scene.materials[f.material].twoSided ? 2.0 : 1.0) * f.area;

  ASSERT_EQ(model.scenes.size(), 1u);
  ASSERT_EQ(model.nodes.size(), scene.objects.size());
  EXPECT_NE(
      std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), "KHR_materials_unlit"),
      model.extensionsUsed.end());
  size_t triangles = 0, probes = 0;
  double area = 0.0;
  for (size_t o = 0; o < model.nodes.size(); ++o) {
    const tinygltf::Node& node = model.nodes[o];
    EXPECT_EQ(node.name, scene.objects[o].name);
    // The scene triangle of this object's (single, planar) face, for radiance queries.
    const Face& face = *std::find_if(scene.faces.begin(), scene.faces.end(),
                                     [&](const Face& f) { return f.object == o; });
    for (const tinygltf::Primitive& prim : model.meshes.at(node.mesh).primitives) {
      EXPECT_EQ(prim.mode, TINYGLTF_MODE_TRIANGLES);
      const tinygltf::Material& material = model.materials.at(prim.material);
      EXPECT_FALSE(material.doubleSided) << node.name;  // each side has triangles of its own
      EXPECT_EQ(material.extensions.count("KHR_materials_unlit"), 1u);
      EXPECT_EQ(material.pbrMetallicRoughness.baseColorFactor,
                (std::vector<double>{1.0, 1.0, 1.0, 1.0}));
      const auto positions = readAccessor<float>(model, prim.attributes.at("POSITION"), 3);
      const auto normals = readAccessor<float>(model, prim.attributes.at("NORMAL"), 3);
      const auto colors = readAccessor<float>(model, prim.attributes.at("COLOR_0"), 3);
      const auto indices = readAccessor<uint32_t>(model, prim.indices, 1);
      ASSERT_EQ(colors.size(), positions.size());
      ASSERT_EQ(normals.size(), positions.size());
      for (float c : colors) {
        EXPECT_GE(c, 0.0f);
        EXPECT_LE(c, 1.0f);
      }
      auto at = [&](const std::vector<float>& v, uint32_t i) {
        return Vec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
      };
      triangles += indices.size() / 3;
      for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const Vec3 a = at(positions, indices[t]), b = at(positions, indices[t + 1]);
        const Vec3 c = at(positions, indices[t + 2]);
        const Vec3 n = glm::cross(b - a, c - a);
        area += 0.5 * glm::length(n);
        // Wound to face the way its side does (the back's triangles against the face normal).
        EXPECT_GT(glm::dot(n, at(normals, indices[t])), 0.0f) << "triangle wound against its side";
        if (o != 0) {
          EXPECT_GT(glm::dot(n, face.normal), 0.0f) << "a one-sided face's back";
        }
      }
      // Probes: the colour is what radiance() gives at the vertex (Ke + rho H / pi, H the
      // average at the welded vertex), clamped to [0, 1].
      const uint32_t vertices = uint32_t(positions.size() / 3);
      for (uint32_t v = 0; v < vertices; v += 13, ++probes) {
        const bool front = glm::dot(at(normals, v), face.normal) > 0.0f;
        const Color expected =
            solution.radiance({at(positions, v), face.normal, face.firstTriangle, front});
        const Color clamped = glm::clamp(expected, Color(0.0f), Color(1.0f));
        // The two-sided wall's back faces out of the closed room: no light reaches it.
        if (!front) {
          EXPECT_LT(maxComponent(at(colors, v)), 1e-6f) << node.name;
        }
        for (int ch = 0; ch < 3; ++ch)
          EXPECT_NEAR(at(colors, v)[ch], clamped[ch], 1e-5f)
              << node.name << " vertex " << v << " channel " << ch;
        EXPECT_NEAR(glm::length(at(normals, v)), 1.0f, 1e-5f);
        EXPECT_GT(std::abs(glm::dot(at(normals, v), face.normal)), 0.99f);
      }
    }
  }
  EXPECT_EQ(triangles, expectedTriangles);
  EXPECT_NEAR(area, sceneArea, 1e-4 * sceneArea);
  EXPECT_GE(probes, 30u);
}

TEST(PatchGlbExport, TexturedFacesCarryIrradianceUnderTheirTexture) {
  // Its primitive shows the texture (embedded, read back as the same image) times the factor on
  // TEXCOORD_0, and its colours are H / pi, so that a viewer's COLOR_0 x base colour is the
  // picture's texel x irradiance.
  const Scene scene = test::litTexturedQuad();
  PatchRadiositySettings settings;
  settings.patchSize = 0.25f;
  settings.cacheDir = "";
  const PatchRadiosity solution(scene, settings);
  const fs::path dir = freshDir("radiosity_textured_glb");
  writeLitMeshGlb((dir / "quad.glb").string(), solution.litMesh());
  test::expectQuadUnderItsTexture(loadGlb(dir / "quad.glb"), scene, solution);
  // Read back as a scene, the quad is textured as it was.
  const Scene back = loadScene((dir / "quad.glb").string());
  ASSERT_EQ(back.materials.size(), 1u);
  ASSERT_TRUE(back.materials[0].rhoTexture);
  EXPECT_NEAR(back.materials[0].rhoTexture.texture->mean().g, 0.5f, 1e-3f);
}

TEST(PatchGlbExport, MissingDirectoryThrowsAndLeavesNothing) {
  const SolvedRoom room(0.25f);
  const fs::path dir = freshDir("radiosity_glb_missing");
  EXPECT_THROW(room.solution.exportGlb((dir / "missing" / "room.glb").string()),
               std::runtime_error);
  EXPECT_FALSE(fs::exists(dir / "missing"));
  EXPECT_TRUE(filesIn(dir).empty());
}

// The neutral writer on its own: colours outside [0, 1] (or NaN) are clamped, a mesh without
// groups is one node, and an inconsistent description is refused before anything is written.
TEST(LitMeshGlb, ClampsColoursAndRefusesBadInput) {
  const fs::path dir = freshDir("radiosity_glb_writer");
  LitMesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  mesh.normals = {Vec3(0, 0, 2), Vec3(0, 0, 1), Vec3(0, 0, 1)};
  const float nan = std::numeric_limits<float>::quiet_NaN();
  mesh.colors = {Color(2.0f, -1.0f, nan), Color(0.25f), Color(1.0f)};
  mesh.indices = {0, 1, 2};
  writeLitMeshGlb((dir / "t.glb").string(), mesh);
  const tinygltf::Model model = loadGlb(dir / "t.glb");
  ASSERT_EQ(model.nodes.size(), 1u);
  EXPECT_EQ(model.nodes[0].name, "radiosity");
  const tinygltf::Primitive& prim = model.meshes.at(0).primitives.at(0);
  EXPECT_FALSE(model.materials.at(prim.material).doubleSided);
  const auto colors = readAccessor<float>(model, prim.attributes.at("COLOR_0"), 3);
  EXPECT_EQ(std::vector<float>(colors.begin(), colors.begin() + 6),
            (std::vector<float>{1.0f, 0.0f, 0.0f, 0.25f, 0.25f, 0.25f}));
  const auto normals = readAccessor<float>(model, prim.attributes.at("NORMAL"), 3);
  EXPECT_EQ(normals[2], 1.0f);

  mesh.indices = {0, 1, 3};
  EXPECT_THROW(writeLitMeshGlb((dir / "bad.glb").string(), mesh), std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir / "bad.glb"));
}

// A bake in physical units is often far below 1 (radiance in W/(sr m^2) of a dim room): the
// exposure scales it by 2^EV before the clamp, and the file says which it was.
TEST(LitMeshGlb, ExposureScalesTheColoursAndIsRecorded) {
  const fs::path dir = freshDir("radiosity_glb_exposure");
  LitMesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  mesh.normals = {Vec3(0, 0, 1), Vec3(0, 0, 1), Vec3(0, 0, 1)};
  mesh.colors = {Color(0.01f), Color(0.05f, 0.02f, 0.2f), Color(0.125f)};
  mesh.indices = {0, 1, 2};
  writeLitMeshGlb((dir / "t.glb").string(), mesh, 3.0f);
  const tinygltf::Model model = loadGlb(dir / "t.glb");
  const tinygltf::Primitive& prim = model.meshes.at(0).primitives.at(0);
  const auto colors = readAccessor<float>(model, prim.attributes.at("COLOR_0"), 3);
  const std::vector<float> expected = {0.08f, 0.08f, 0.08f, 0.4f, 0.16f, 1.0f, 1.0f, 1.0f, 1.0f};
  ASSERT_EQ(colors.size(), expected.size());
  for (size_t k = 0; k < colors.size(); ++k) EXPECT_NEAR(colors[k], expected[k], 1e-6) << k;
  const tinygltf::Value& baked = model.asset.extras.Get("radiosity");
  ASSERT_TRUE(baked.IsObject());
  EXPECT_EQ(baked.Get("exposure_ev").GetNumberAsDouble(), 3.0);
}

}  // namespace
}  // namespace rad
