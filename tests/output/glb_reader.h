#pragma once
// Reading back the .glb files the exporters write (src/output/gltf_export.h), for the tests.

// Declarations only, with the switches of the one implementation in src/scene/io/gltf_loader.cpp.
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <gtest/gtest.h>
#include <radiosity/scene_loader.h>
#include <radiosity/surface_solution.h>
#include <radiosity/texture.h>
#include <tiny_gltf.h>

#include <cstring>
#include <filesystem>
#include <glm/gtc/constants.hpp>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace rad::test {

/// Images stay encoded (this tinygltf decodes none): their bytes are in their bufferView.
inline bool keepImage(tinygltf::Image*, const int, std::string*, std::string*, int, int,
                      const unsigned char*, int, void*) {
  return true;
}

inline tinygltf::Model loadGlb(const std::filesystem::path& path) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&keepImage, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, path.string())) << err;
  EXPECT_TRUE(err.empty()) << err;
  return model;
}

/// Tightly packed accessor data (the exporter writes no strides) as `count x components` values.
template <typename T>
std::vector<T> readAccessor(const tinygltf::Model& model, int index, int components) {
  const tinygltf::Accessor& a = model.accessors.at(size_t(index));
  const tinygltf::BufferView& view = model.bufferViews.at(size_t(a.bufferView));
  const std::vector<unsigned char>& data = model.buffers.at(size_t(view.buffer)).data;
  std::vector<T> out(a.count * size_t(components));
  const size_t offset = view.byteOffset + a.byteOffset;
  EXPECT_LE(offset + out.size() * sizeof(T), data.size());
  std::memcpy(out.data(), data.data() + offset, out.size() * sizeof(T));
  return out;
}

/// The textured quad of tests/data/scene/textured (2 x 1 m, u along its length, its texture half
/// black and half white at factor 0.8) under a point light: what the exports' texture tests solve.
inline Scene litTexturedQuad() {
  Scene scene = loadScene(std::string(RADIOSITY_TEST_DATA_DIR) + "/scene/textured/quad.obj");
  Light light;
  light.position = Vec3(1.0f, 1.0f, 0.5f);
  light.intensity = Color(2.0f);
  scene.lights = {light};
  return scene;
}

/// An export of litTexturedQuad(), read back: one material showing the embedded image times the
/// factor on TEXCOORD_0 (u = x / 2), and at every vertex the solution's H / pi.
inline void expectQuadUnderItsTexture(const tinygltf::Model& model, const Scene& scene,
                                      const SurfaceSolution& solution) {
  ASSERT_EQ(model.materials.size(), 1u);
  const tinygltf::Material& material = model.materials[0];
  EXPECT_NEAR(material.pbrMetallicRoughness.baseColorFactor[1], 0.8, 1e-6);
  ASSERT_EQ(material.pbrMetallicRoughness.baseColorTexture.index, 0);
  ASSERT_EQ(model.images.size(), 1u);
  const tinygltf::BufferView& view = model.bufferViews.at(size_t(model.images[0].bufferView));
  const std::span<const uint8_t> png(model.buffers[0].data.data() + view.byteOffset,
                                     view.byteLength);
  const std::shared_ptr<const Texture> image = Texture::decode(png, "exported");
  EXPECT_EQ(image->width(), 16);
  EXPECT_NEAR(image->mean().r, 0.5f, 1e-3f);
  const tinygltf::Primitive& prim = model.meshes.at(0).primitives.at(0);
  ASSERT_TRUE(prim.attributes.count("TEXCOORD_0"));
  const std::vector<float> p = readAccessor<float>(model, prim.attributes.at("POSITION"), 3);
  const std::vector<float> c = readAccessor<float>(model, prim.attributes.at("COLOR_0"), 3);
  const std::vector<float> uv = readAccessor<float>(model, prim.attributes.at("TEXCOORD_0"), 2);
  for (size_t v = 0; v < p.size() / 3; ++v) {
    const Vec3 point(p[3 * v], p[3 * v + 1], p[3 * v + 2]);
    EXPECT_NEAR(uv[2 * v], point.x / 2.0f, 1e-5f);
    SurfaceHit hit{point, Vec3(0, 1, 0), 0, true};
    hit.barycentric = scene.locateOnFace(0, point, hit.triangle);
    EXPECT_NEAR(c[3 * v], solution.irradiance(hit).r / glm::pi<float>(), 1e-4f) << v;
  }
}

}  // namespace rad::test
