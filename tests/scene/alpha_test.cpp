// Coverage as the files give it (Material: alphaMode, alpha, alphaCutoff, transmission): a
// texture's alpha kept linear, glTF's alphaMode, alphaCutoff, baseColorFactor alpha, COLOR_0
// alpha and KHR_materials_transmission, MTL d and map_d, and the scene file's keys. The files
// are written here: a 1 x 1 quad facing +z whose texture coordinates are its x and y, its 2 x 1
// texture (clamped) transparent on the left (alpha 0) and opaque on the right (alpha 255).
#include <gtest/gtest.h>
#include <radiosity/error.h>
#include <radiosity/scene_loader.h>
#include <radiosity/texture.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "output/image_formats.h"
#include "scene_summary.h"

namespace rad {
namespace {

std::string base64(const std::string& bytes) {
  static const char* kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const size_t n = std::min<size_t>(3, bytes.size() - i);
    uint32_t v = 0;
    for (size_t k = 0; k < 3; ++k) v = v << 8 | (k < n ? uint8_t(bytes[i + k]) : 0u);
    for (size_t k = 0; k < 4; ++k) out += k <= n ? kDigits[(v >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

// sRGB 188 (linear 0.50289) everywhere; alpha 0 on the left texel, 255 on the right.
std::string halfTransparentPng() {
  return encodePng(2, 1, {188, 188, 188, 0, 188, 188, 188, 255}, 4);
}

template <typename T>
void append(std::string& buffer, const std::vector<T>& values) {
  buffer.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

// The quad with COLOR_0 alpha (normalized bytes) 1, 1, 0, 1 at its corners (0,0), (1,0),
// (1,1), (0,1), material `material` (a JSON object's members).
std::string quadGltf(const std::string& material) {
  std::string buffer;
  append(buffer, std::vector<float>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
  append(buffer, std::vector<float>{0, 0, 1, 0, 1, 1, 0, 1});
  append(buffer, std::vector<uint8_t>{9, 9, 9, 255, 9, 9, 9, 255, 9, 9, 9, 0, 9, 9, 9, 255});
  append(buffer, std::vector<uint16_t>{0, 1, 2, 0, 2, 3});
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
  "nodes":[{"mesh":0,"name":"quad"}],
  "meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1,"COLOR_0":2},
    "indices":3,"material":0}]}],
  "materials":[{"name":"leaf",)" +
         material + R"(}],
  "textures":[{"source":0,"sampler":0}],
  "samplers":[{"wrapS":33071,"wrapT":33071}],
  "images":[{"uri":"data:image/png;base64,)" +
         base64(halfTransparentPng()) + R"("}],
  "accessors":[
    {"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
    {"bufferView":1,"componentType":5126,"count":4,"type":"VEC2"},
    {"bufferView":2,"componentType":5121,"normalized":true,"count":4,"type":"VEC4"},
    {"bufferView":3,"componentType":5123,"count":6,"type":"SCALAR"}],
  "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},
    {"buffer":0,"byteOffset":48,"byteLength":32},{"buffer":0,"byteOffset":80,"byteLength":16},
    {"buffer":0,"byteOffset":96,"byteLength":12}],
  "buffers":[{"byteLength":108,"uri":"data:application/octet-stream;base64,)" +
         base64(buffer) + R"("}]})";
}

const std::string kMaskedLeaf =
    R"("alphaMode":"MASK","alphaCutoff":0.3,
    "pbrMetallicRoughness":{"baseColorFactor":[1,1,1,0.8],"baseColorTexture":{"index":0}},
    "extensions":{"KHR_materials_transmission":{"transmissionFactor":0.25}})";

// The coverage at the point (x, y) of the quad.
float coverageAt(const Scene& scene, float x, float y) {
  for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
    const Vec2 b = scene.barycentricOf(t, Vec3(x, y, 0));
    if (b.x >= 0 && b.y >= 0 && b.x + b.y <= 1) return scene.coverageAt(t, b);
  }
  ADD_FAILURE() << "no triangle at " << x << ", " << y;
  return -1.0f;
}

TEST(Alpha, TextureKeepsAlphaLinearBesideItsSrgbColour) {
  const std::string png = halfTransparentPng();
  const auto texture = Texture::decode(
      std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(png.data()), png.size()), "a");
  ASSERT_TRUE(texture->hasAlpha());
  constexpr TextureWrap kClamp = TextureWrap::ClampToEdge;
  // Alpha is not sRGB-decoded: 0 and 255 are 0 and 1, their mean 0.5 (to the 16-bit texels'
  // 1 / 65535); the colour is (0.50289).
  EXPECT_NEAR(texture->meanAlpha(), 0.5f, 2e-5f);
  EXPECT_NEAR(texture->sampleAlpha(Vec2(0.1f, 0.5f), 0.0f, kClamp, kClamp), 0.0f, 1e-6f);
  EXPECT_NEAR(texture->sampleAlpha(Vec2(0.9f, 0.5f), 0.0f, kClamp, kClamp), 1.0f, 1e-6f);
  EXPECT_NEAR(texture->mean().g, 0.50289f, 1e-4f);
  const std::string rgb = encodePng(1, 1, {188, 188, 188});
  EXPECT_FALSE(
      Texture::decode(
          std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(rgb.data()), rgb.size()), "b")
          ->hasAlpha());
}

TEST(Alpha, GltfMaskCutoffFactorVertexAlphaAndTransmission) {
  const auto dir = test::scratchDir("alpha_gltf");
  const Scene scene = loadScene(test::writeFile(dir / "leaf.gltf", quadGltf(kMaskedLeaf)));
  ASSERT_EQ(scene.materials.size(), 1u);
  const Material& m = scene.materials[0];
  EXPECT_EQ(m.alphaMode, AlphaMode::Mask);
  EXPECT_FLOAT_EQ(m.alphaCutoff, 0.3f);
  EXPECT_FLOAT_EQ(m.alpha, 0.8f);
  EXPECT_FLOAT_EQ(m.transmission, 0.25f);
  ASSERT_TRUE(m.alphaTexture);
  ASSERT_EQ(scene.vertexAlpha.size(), scene.positions.size());
  EXPECT_FALSE(m.opaque());
  // (0.1, 0.1): texel alpha 0, cut away. (0.9, 0.1): 0.8 x 1 x vertex alpha 0.9 (0.1 of the
  // way to the corner of alpha 0) = 0.72 >= 0.3, kept, times 1 - 0.25. Near (1, 1) the vertex
  // alpha falls to 0: cut away.
  EXPECT_FLOAT_EQ(coverageAt(scene, 0.1f, 0.1f), 0.0f);
  EXPECT_FLOAT_EQ(coverageAt(scene, 0.9f, 0.1f), 0.75f);
  EXPECT_FLOAT_EQ(coverageAt(scene, 0.95f, 0.9f), 0.0f);
}

TEST(Alpha, SceneFileMakesItBlendAndChecksItsKeys) {
  const auto dir = test::scratchDir("alpha_json");
  test::writeFile(dir / "leaf.gltf", quadGltf(kMaskedLeaf));
  const std::string scene =
      test::writeFile(dir / "scene.json", R"({"geometry":[{"file":"leaf.gltf"}],"materials":{"leaf":
        {"alpha_mode":"blend","transmission":0}}})");
  // Blend: the alpha itself, 0.72 at (0.9, 0.1) (above), no transmission.
  EXPECT_NEAR(coverageAt(loadScene(scene), 0.9f, 0.1f), 0.72f, 1e-5f);
  const std::string bad =
      test::writeFile(dir / "bad.json", R"({"geometry":[{"file":"leaf.gltf"}],"materials":{"leaf":
        {"alpha_mode":"cutout"}}})");
  const std::string error = test::errorOf([&] { loadScene(bad); });
  EXPECT_NE(error.find("/materials/leaf/alpha_mode"), std::string::npos) << error;
  const std::string range =
      test::writeFile(dir / "range.json", R"({"geometry":[{"file":"leaf.gltf"}],"materials":{"leaf":
        {"alpha":1.5}}})");
  EXPECT_NE(test::errorOf([&] { loadScene(range); }).find("out of range"), std::string::npos);
}

TEST(Alpha, MtlDissolveIsBlendAndMapDIsMask) {
  const auto dir = test::scratchDir("alpha_obj");
  const std::string png = halfTransparentPng();
  test::writeFile(dir / "leaf.png", png);
  test::writeFile(dir / "quad.mtl",
                  "newmtl glass\nKd 0.5 0.5 0.5\nd 0.3\n"
                  "newmtl leaf\nKd 0.5 0.5 0.5\nmap_d -clamp on leaf.png\n");
  const std::string obj = test::writeFile(
      dir / "quad.obj",
      "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
      "vt 0 1\nvt 1 1\nvt 1 0\nvt 0 0\n"
      "usemtl leaf\nf 1/1 2/2 3/3 4/4\nusemtl glass\nf 5/1 6/2 7/3 8/4\n");
  const Scene scene = loadScene(obj);
  for (const Material& m : scene.materials) {
    SCOPED_TRACE(m.name);
    if (m.name == "glass") {
      EXPECT_EQ(m.alphaMode, AlphaMode::Blend);
      EXPECT_FLOAT_EQ(m.alpha, 0.3f);
    } else {
      EXPECT_EQ(m.alphaMode, AlphaMode::Mask);
      EXPECT_TRUE(m.alphaTexture && m.alphaTexture.texture->hasAlpha());
    }
  }
  EXPECT_FLOAT_EQ(coverageAt(scene, 0.1f, 0.5f), 0.0f);
  EXPECT_FLOAT_EQ(coverageAt(scene, 0.9f, 0.5f), 1.0f);
}

}  // namespace
}  // namespace rad
