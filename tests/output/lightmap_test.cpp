// The lightmap atlas export: charts inside the atlas and apart, texels that hold the light of
// their own face (gutters too), the atlas read at a vertex's second UV set giving what the solver
// has there, and the .glb and .exr pair that carries it.
#include <gtest/gtest.h>
#include <radiosity/error.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/scene_builder.h>
#include <radiosity/scene_loader.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>

#include "output/glb_reader.h"
#include "output/lightmap_atlas.h"

namespace rad {
namespace {

// The atlas read as a GPU reads it: bilinear between texel centres (glTF texture coordinates).
Color bilinear(const Image& image, Vec2 uv) {
  const float x = uv.x * float(image.width) - 0.5f, y = uv.y * float(image.height) - 0.5f;
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const float fx = x - float(x0), fy = y - float(y0);
  auto at = [&](int i, int j) {
    return image.at(std::clamp(i, 0, image.width - 1), std::clamp(j, 0, image.height - 1));
  };
  return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
         fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
}

// A solution whose irradiance is known everywhere: a point light of intensity I at height h
// over the plane z = 0 gives H = I h / d^3 (d the distance), the closed form that the atlas must
// hold texel by texel; on other planes a value that tells the side and the face apart.
class PointLightOverFloor : public SurfaceSolution {
 public:
  static constexpr float kIntensity = 2.0f, kHeight = 0.7f;
  explicit PointLightOverFloor(const Scene& scene) : scene_(scene) {}
  static Color closedForm(const SurfaceHit& hit) {
    if (std::abs(hit.normal.z) < 0.5f) return Color(hit.frontFace ? 1.0f : 2.0f);
    const Vec3 d = Vec3(0.3f, 0.4f, kHeight) - hit.point;
    return Color(kIntensity * kHeight / std::pow(glm::length(d), 3.0f));
  }
  const Scene& scene() const override { return scene_; }
  size_t elementCount() const override { return 0; }
  SurfaceElement element(size_t) const override { return {}; }
  LitMesh litMesh() const override { return {}; }
  Color irradiance(const SurfaceHit& hit) const override { return closedForm(hit); }
  Color radiance(const SurfaceHit& hit) const override {
    return 0.5f * closedForm(hit) / glm::pi<float>();
  }

 private:
  const Scene& scene_;
};

// A 1 x 1 floor of two triangles, a wall of one face (two-sided, so two charts) and a small
// triangle beside them.
Scene floorAndWall() {
  SceneBuilder b("floor and wall");
  const uint32_t white = b.addMaterial({"white", Color(0.5f), Color(0.0f), false});
  const uint32_t card = b.addMaterial({"card", Color(0.5f), Color(0.0f), true});
  const std::array<uint32_t, 4> floor{b.addVertex({0, 0, 0}, "f0"), b.addVertex({1, 0, 0}, "f1"),
                                      b.addVertex({1, 1, 0}, "f2"), b.addVertex({0, 1, 0}, "f3")};
  b.addPolygon(floor, white, b.addObject("floor"), "floor");
  const std::array<uint32_t, 4> wall{b.addVertex({0, 1, 0}, "w0"), b.addVertex({1, 1, 0}, "w1"),
                                     b.addVertex({1, 1, 0.5f}, "w2"),
                                     b.addVertex({0, 1, 0.5f}, "w3")};
  b.addPolygon(wall, card, b.addObject("wall"), "wall");
  const std::array<uint32_t, 3> small{b.addVertex({2, 0, 0}, "s0"), b.addVertex({2.1f, 0, 0}, "s1"),
                                      b.addVertex({2, 0.05f, 0}, "s2")};
  b.addPolygon(small, white, b.addObject("small"), "small");
  return b.build();
}

bool overlap(const LightmapChart& a, const LightmapChart& b) {
  return a.x < b.x + b.width && b.x < a.x + a.width && a.y < b.y + b.height && b.y < a.y + a.height;
}

void expectChartsInsideAndApart(const LightmapAtlas& atlas) {
  for (size_t i = 0; i < atlas.charts.size(); ++i) {
    const LightmapChart& c = atlas.charts[i];
    EXPECT_GE(c.x, 0);
    EXPECT_GE(c.y, 0);
    EXPECT_LE(c.x + c.width, atlas.size);
    EXPECT_LE(c.y + c.height, atlas.size);
    for (size_t j = 0; j < i; ++j) EXPECT_FALSE(overlap(c, atlas.charts[j])) << i << " " << j;
  }
}

TEST(LightmapAtlas, EveryFaceSideHasAChartInsideTheAtlasApartFromTheOthers) {
  const Scene scene = loadScene("cornell");
  const LightmapAtlas atlas = packLightmapAtlas(scene, 512);
  size_t sides = 0;
  for (const Face& f : scene.faces) sides += scene.materials[f.material].twoSided ? 2 : 1;
  EXPECT_EQ(atlas.charts.size(), sides);
  expectChartsInsideAndApart(atlas);
  // Every vertex of a face maps inside its chart, a gutter away from its edge.
  for (const LightmapChart& c : atlas.charts) {
    const Face& face = scene.faces[c.face];
    for (uint32_t t = face.firstTriangle; t < face.firstTriangle + face.triangleCount; ++t)
      for (int k = 0; k < 3; ++k) {
        const Vec2 texel =
            atlas.texcoordOf(c, scene.positions[scene.triangles[t][k]]) * float(atlas.size);
        EXPECT_GE(texel.x, float(c.x + LightmapAtlas::kGutter) - 1e-3f);
        EXPECT_GE(texel.y, float(c.y + LightmapAtlas::kGutter) - 1e-3f);
        EXPECT_LE(texel.x, float(c.x + c.width - LightmapAtlas::kGutter) + 1e-3f);
        EXPECT_LE(texel.y, float(c.y + c.height - LightmapAtlas::kGutter) + 1e-3f);
      }
  }
  // The charts fill the atlas: the density is the largest that packs, within the search's step.
  double used = 0.0;
  for (const LightmapChart& c : atlas.charts) used += double(c.width) * c.height;
  EXPECT_GT(used / (512.0 * 512.0), 0.6);
}

TEST(LightmapAtlas, TexelsHoldTheClosedFormIrradianceOfTheirOwnFaceAndSide) {
  const Scene scene = floorAndWall();
  const PointLightOverFloor solution(scene);
  const LightmapAtlas atlas = packLightmapAtlas(scene, 256);
  ASSERT_EQ(atlas.charts.size(), 4u);  // floor, wall front and back, small triangle
  expectChartsInsideAndApart(atlas);
  const LightmapImages images = shadeLightmapAtlas(atlas, solution);
  std::array<int, 3> insideTexels{};
  for (const LightmapChart& c : atlas.charts) {
    const uint32_t object = scene.faces[c.face].object;
    for (int y = 0; y < c.height; ++y)
      for (int x = 0; x < c.width; ++x) {
        const Color h = images.irradiance.at(c.x + x, c.y + y);
        if (object == 1) {
          // The wall: each texel its own side's value, gutters included.
          EXPECT_EQ(h, Color(c.backSide ? 2.0f : 1.0f));
          continue;
        }
        // A texel whose centre lies on the floor or the small triangle: H = I h / d^3 there.
        const float u = (float(x - LightmapAtlas::kGutter) + 0.5f) / atlas.texelsPerUnit;
        const float v = (float(y - LightmapAtlas::kGutter) + 0.5f) / atlas.texelsPerUnit;
        const Vec3 p = c.origin + c.uAxis * u + c.vAxis * v;
        const bool inside = object == 0 ? p.x > 0 && p.x < 1 && p.y > 0 && p.y < 1
                                        : p.x > 2 && p.y > 0 && (p.x - 2) / 0.1f + p.y / 0.05f < 1;
        if (!inside) continue;
        const Vec3 d = Vec3(0.3f, 0.4f, PointLightOverFloor::kHeight) - p;
        const float expected = PointLightOverFloor::kIntensity * PointLightOverFloor::kHeight /
                               std::pow(glm::length(d), 3.0f);
        EXPECT_NEAR(h.r, expected, 1e-4f * expected);
        EXPECT_NEAR(images.radiance.at(c.x + x, c.y + y).r, 0.5f * h.r / glm::pi<float>(),
                    1e-6f * h.r);
        ++insideTexels[object];
      }
  }
  // The small triangle is 0.1 x 0.05: at the atlas's density it still gets texels of its own.
  EXPECT_GT(insideTexels[0], 10000);
  EXPECT_GT(insideTexels[2], 4);
  // Texels between the charts stay black (nothing reads them).
  EXPECT_EQ(images.irradiance.at(atlas.size - 1, atlas.size - 1), Color(0.0f));
}

PatchRadiosity cornellSolution(const Scene& scene) {
  PatchRadiositySettings settings;
  settings.targetPatches = 1500;
  settings.formFactorRays = 256;
  return PatchModel(scene, settings).solve(scene.lights);
}

// The check: the atlas read at a vertex's second UV set gives the irradiance the solver
// has there, within 2%.
TEST(LightmapAtlas, AtlasAtEachVertexGivesTheSolversIrradianceThere) {
  const Scene scene = loadScene("cornell");
  const PatchRadiosity solution = cornellSolution(scene);
  const LightmapAtlas atlas = packLightmapAtlas(scene, 1024);
  const LightmapImages images = shadeLightmapAtlas(atlas, solution);
  double worst = 0.0;
  size_t corners = 0;
  for (const LightmapChart& c : atlas.charts) {
    const Face& face = scene.faces[c.face];
    for (uint32_t t = face.firstTriangle; t < face.firstTriangle + face.triangleCount; ++t)
      for (int k = 0; k < 3; ++k) {
        const Vec3 p = scene.positions[scene.triangles[t][k]];
        const SurfaceHit hit{p, face.normal, t, !c.backSide,
                             Vec2(k == 1 ? 1.0f : 0.0f, k == 2 ? 1.0f : 0.0f)};
        const Color expected = solution.irradiance(hit);
        const Color read = bilinear(images.irradiance, atlas.texcoordOf(c, p));
        const double error = maxComponent(glm::abs(read - expected)) /
                             std::max(double(maxComponent(expected)), 1e-12);
        worst = std::max(worst, error);
        ++corners;
      }
  }
  EXPECT_GT(corners, 30u);
  EXPECT_LT(worst, 0.02);
  std::printf("atlas vs solver at %zu corners: worst %.3f%%\n", corners, 100.0 * worst);
}

// What `solve --export FILE.glb --lightmap SIZE` writes: the scene's triangles with TEXCOORD_1
// into the atlas shown by an unlit material, and the irradiance atlas as EXR beside, named in the
// asset's extras, texel for texel the atlas's.
TEST(LightmapAtlas, GlbShowsTheAtlasAndNamesTheIrradianceExrBesideIt) {
  const Scene scene = loadScene("cornell");
  const PatchRadiosity solution = cornellSolution(scene);
  const auto dir = std::filesystem::path(RADIOSITY_BINARY_DIR) / "lightmap_glb_test";
  std::filesystem::create_directories(dir);
  const std::string glb = (dir / "cornell.glb").string();
  solution.exportLightmappedGlb(glb, 256, 1.0f);
  const std::string exr = lightmapIrradiancePath(glb);
  EXPECT_EQ(exr, (dir / "cornell.lightmap.exr").string());

  const tinygltf::Model model = test::loadGlb(glb);
  ASSERT_EQ(model.materials.size(), 1u);
  const tinygltf::Material& m = model.materials[0];
  EXPECT_TRUE(m.extensions.count("KHR_materials_unlit"));
  EXPECT_EQ(m.pbrMetallicRoughness.baseColorTexture.texCoord, 1);
  const tinygltf::Value& lightmap = model.asset.extras.Get("radiosity").Get("lightmap");
  EXPECT_EQ(lightmap.Get("irradiance_uri").Get<std::string>(), "cornell.lightmap.exr");
  EXPECT_EQ(lightmap.Get("size").GetNumberAsInt(), 256);
  size_t triangles = 0;
  for (const tinygltf::Mesh& mesh : model.meshes)
    for (const tinygltf::Primitive& p : mesh.primitives) {
      EXPECT_FALSE(p.attributes.count("COLOR_0"));  // the lightmap is the light
      ASSERT_TRUE(p.attributes.count("TEXCOORD_1"));
      for (float uv : test::readAccessor<float>(model, p.attributes.at("TEXCOORD_1"), 2)) {
        EXPECT_GT(uv, 0.0f);
        EXPECT_LT(uv, 1.0f);
      }
      triangles += model.accessors[size_t(p.indices)].count / 3;
    }
  size_t sides = 0;
  for (const Face& f : scene.faces)
    sides += f.triangleCount * (scene.materials[f.material].twoSided ? 2 : 1);
  EXPECT_EQ(triangles, sides);  // the scene's own triangles, uncut

  const Image written = readImage(exr);
  const Image expected = shadeLightmapAtlas(packLightmapAtlas(scene, 256), solution).irradiance;
  ASSERT_EQ(written.width, 256);
  ASSERT_EQ(written.height, 256);
  EXPECT_EQ(written.pixels, expected.pixels);  // float EXR: the very values
}

TEST(LightmapAtlas, SmallestChartsThatDoNotFitAreRefusedByMessage) {
  const Scene scene = loadScene("cornell");
  try {
    packLightmapAtlas(scene, 16);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("larger size"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rad
