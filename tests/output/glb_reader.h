#pragma once
// Reading back the .glb files the exporters write (src/output/gltf_export.h), for the tests.

// Declarations only, with the switches of the one implementation in src/scene/io/gltf_loader.cpp.
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cstring>
#include <filesystem>
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

}  // namespace rad::test
