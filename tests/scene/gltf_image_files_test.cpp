// glTF images in files of their own, as exporters write them: a .gltf, its .bin and PNG/JPEG
// files beside it, named by relative, percent-encoded URIs (glTF 2.0, 3.3).
//
// tests/data/scene/external/quads.gltf holds ten 1 x 1 quads, each with its own material
// (baseColorFactor 0.8; 1 for "rgb16", glTF's usual white scale under a texture, which is no
// reflectance of 1 to warn of) and image; its buffer is "quad data.bin" (URI quad%20data.bin).
// Every image is a uniform 4 x 4 field of sRGB 188, the PNGs written byte by byte by a script
// (Python's zlib; 16-bit ones 188 x 257): grey ("textures/grey 8.png", URI textures/grey%208.png),
// grey+alpha, RGB, RGBA, palette, 16-bit grey, RGB and RGBA, "100%.png" (URI 100%25.png), and an 8
// x 8 JPEG by ffmpeg (`-f lavfi -i color=c=0xBCBCBC:s=8x8 -frames:v 1 -q:v 1`). sRGB 188 is linear
// 0.502886 (IEC 61966-2-1: ((188/255 + 0.055) / 1.055)^2.4, computed apart from the code under
// test).
#include <gtest/gtest.h>
#include <radiosity/scene_loader.h>
#include <radiosity/texture.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "scene_summary.h"

namespace fs = std::filesystem;

namespace rad {
namespace {

const std::string kExternal = test::kData + "external/";
constexpr float kLinear188 = 0.502886f;

void expectEveryImageRead(const Scene& scene) {
  ASSERT_TRUE(scene.warnings.empty()) << scene.warnings.front();
  ASSERT_EQ(scene.materials.size(), 10u);
  for (const Material& m : scene.materials) {
    SCOPED_TRACE(m.name);
    ASSERT_TRUE(m.rhoTexture);
    // ffmpeg's JPEG goes through YUV and quantization: within two code values (1/255 at 188 is
    // 0.0045 linear).
    const float tolerance = m.name == "jpeg" ? 0.01f : 1e-4f;
    EXPECT_NEAR(m.rhoTexture.texture->mean().g, kLinear188, tolerance);
    EXPECT_NEAR(m.rhoTexture.texture->mean().r, kLinear188, tolerance);
  }
}

TEST(GltfImageFiles, EveryPngAndJpegFormReadFromFilesBesideTheGltf) {
  expectEveryImageRead(loadScene(kExternal + "quads.gltf"));
}

TEST(GltfImageFiles, ReadFromAnotherWorkingDirectoryAndThroughASceneFileElsewhere) {
  const fs::path dir = fs::path(::testing::TempDir()) / "radiosity_gltf_images_elsewhere";
  fs::create_directories(dir);
  const fs::path before = fs::current_path();
  fs::current_path(dir);
  // A relative path from here to the glTF: its images resolve against the glTF's folder.
  expectEveryImageRead(loadScene(fs::relative(kExternal + "quads.gltf", dir).string()));
  fs::current_path(before);
  // A scene file in another folder naming the glTF by a path relative to itself.
  const fs::path sceneFile = dir / "uses_quads.json";
  std::ofstream(sceneFile) << R"({"geometry": [{"file": ")"
                           << fs::relative(kExternal + "quads.gltf", dir).generic_string()
                           << R"("}]})";
  expectEveryImageRead(loadScene(sceneFile.string()));
  fs::remove_all(dir);
}

TEST(GltfImageFiles, AMissingOrBrokenImageIsAWarningNamingTheFileAndWhy) {
  const fs::path dir = fs::path(::testing::TempDir()) / "radiosity_gltf_images_missing";
  fs::remove_all(dir);
  fs::copy(kExternal, dir, fs::copy_options::recursive);
  fs::remove(dir / "rgb.png");                        // missing
  std::ofstream(dir / "rgba.png") << "not an image";  // unreadable as PNG
  const Scene scene = loadScene((dir / "quads.gltf").string());
  ASSERT_EQ(scene.warnings.size(), 2u);
  const std::string& missing = scene.warnings[0];
  EXPECT_NE(missing.find((dir / "rgb.png").string()), std::string::npos) << missing;
  EXPECT_NE(missing.find("cannot open"), std::string::npos) << missing;
  EXPECT_NE(missing.find("'rgb'"), std::string::npos) << missing;  // the material
  const std::string& broken = scene.warnings[1];
  EXPECT_NE(broken.find((dir / "rgba.png").string()), std::string::npos) << broken;
  EXPECT_NE(broken.find("not a PNG or JPEG"), std::string::npos) << broken;
  // Those two keep their factor alone; the others still read theirs.
  for (const Material& m : scene.materials) {
    const bool lost = m.name == "rgb" || m.name == "rgba";
    EXPECT_EQ(bool(m.rhoTexture), !lost) << m.name;
    if (lost) {
      EXPECT_NEAR(m.rho.g, 0.8f, 1e-6f) << m.name;
    }
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rad
