// Textures: decoding in linear colour, filtered lookups, the loaders' texture maps and the
// reflectance a patch takes from them. The files in tests/data/scene/textured were written once
// by a script (Python's zlib): half.png is 16 x 8 texels, its left half black (0) and its right
// white (255); grey.png is 4 x 4 of sRGB 188; quad.obj / quad.gltf are a 2 x 1 quad facing up
// whose u runs along its length (0 to 1), material factor 0.8, the glTF's texture embedded with
// a clamping sampler and KHR_texture_transform scale (0.5, 1), offset (0.5, 0): the image's white
// half only.
#include <gtest/gtest.h>
#include <radiosity/error.h>
#include <radiosity/scene_builder.h>
#include <radiosity/scene_loader.h>
#include <radiosity/texture.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <span>

#include "core/address_space_limit.h"
#include "patch/patch_mesh.h"
#include "scene_summary.h"

namespace fs = std::filesystem;

namespace rad {
namespace {

const std::string kTextured = test::kData + "textured/";

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(Texture, SrgbMidGreyDecodesToLinear) {
  // sRGB 188 / 255 = 0.73725; linear ((0.73725 + 0.055) / 1.055)^2.4 = 0.50289 (IEC 61966-2-1).
  const std::shared_ptr<const Texture> grey = Texture::load(kTextured + "grey.png");
  EXPECT_EQ(grey->width(), 4);
  EXPECT_NEAR(grey->mean().g, 0.50289f, 1e-4f);
  EXPECT_NEAR(srgbToLinear(0.5f), 0.21404f, 1e-5f);
}

TEST(Texture, FootprintsAverageAndWrapsFold) {
  const std::shared_ptr<const Texture> half = Texture::load(kTextured + "half.png");
  constexpr TextureWrap kRepeat = TextureWrap::Repeat, kClamp = TextureWrap::ClampToEdge,
                        kMirror = TextureWrap::MirroredRepeat;
  EXPECT_NEAR(half->mean().r, 0.5f, 1e-4f);
  EXPECT_NEAR(half->sample(Vec2(0.2f, 0.5f), 0.0f, kRepeat, kRepeat).r, 0.0f, 1e-4f);
  EXPECT_NEAR(half->sample(Vec2(0.8f, 0.5f), 0.0f, kRepeat, kRepeat).r, 1.0f, 1e-4f);
  // A footprint the size of the image is its mean; one of a quarter of it, centred on a half's
  // middle, sees that half only.
  EXPECT_NEAR(half->sample(Vec2(0.5f, 0.5f), 1.0f, kClamp, kClamp).r, 0.5f, 1e-3f);
  EXPECT_NEAR(half->sample(Vec2(0.75f, 0.5f), 0.25f, kClamp, kClamp).r, 1.0f, 1e-3f);
  // u = 1.2: repeated it is 0.2 (black), clamped the last column (white), mirrored 0.8 (white).
  EXPECT_NEAR(half->sample(Vec2(1.2f, 0.5f), 0.0f, kRepeat, kRepeat).r, 0.0f, 1e-4f);
  EXPECT_NEAR(half->sample(Vec2(1.2f, 0.5f), 0.0f, kClamp, kClamp).r, 1.0f, 1e-4f);
  EXPECT_NEAR(half->sample(Vec2(1.2f, 0.5f), 0.0f, kMirror, kMirror).r, 1.0f, 1e-4f);
  EXPECT_NEAR(half->sample(Vec2(-0.8f, 0.5f), 0.0f, kRepeat, kRepeat).r, 0.0f, 1e-4f);
}

TEST(Texture, ATextureThatWouldNotFitIsRefusedBeforeDecoding) {
  // A PNG whose header claims 16,000 x 16,000 texels (its data a few bytes): decoding would need
  // about 6.7 GB; with 64 MB of address space left, refused by message before any allocation.
  std::string png = readBytes(kTextured + "half.png");
  const uint32_t side = 16000;
  for (int at : {16, 20})  // IHDR's width and height, big-endian
    for (int k = 0; k < 4; ++k) png[size_t(at + k)] = char((side >> (24 - 8 * k)) & 0xff);
  const test::AddressSpaceLimit limit(uint64_t(64) << 20);
  if (!limit.lowered()) GTEST_SKIP() << "cannot lower the address-space limit here";
  const std::string m = test::errorOf([&] {
    Texture::decode(
        std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(png.data()), png.size()),
        "huge.png");
  });
  EXPECT_NE(m.find("huge.png"), std::string::npos) << m;
  EXPECT_NE(m.find("16000 x 16000"), std::string::npos) << m;
}

TEST(Texture, NotAnImageIsAnInputErrorNamingTheFile) {
  const std::string m = test::errorOf([] { Texture::load(kTextured + "quad.obj"); });
  EXPECT_NE(m.find("quad.obj"), std::string::npos) << m;
  EXPECT_NE(test::errorOf([] { Texture::load(kTextured + "absent.png"); }).find("absent.png"),
            std::string::npos);
}

// Each patch's reflectance, left to right along the quad.
std::vector<float> patchReflectances(const Scene& scene, float patchSize) {
  const PatchMesh mesh(scene, {patchSize, 0});
  std::vector<std::pair<float, float>> byX;
  for (const Patch& p : mesh.patches()) byX.push_back({p.centroid.x, p.rho.g});
  std::sort(byX.begin(), byX.end());
  std::vector<float> rho;
  for (const auto& [x, r] : byX) rho.push_back(r);
  return rho;
}

TEST(Texture, PatchTakesTheTexturesMeanOverItsFootprint) {
  // The OBJ quad at factor 0.8: a patch over the white half only gets 0.8 (linear), one over
  // the black half 0, one over both 0.4.
  const Scene scene = loadScene(kTextured + "quad.obj");
  ASSERT_TRUE(scene.warnings.empty()) << scene.warnings.front();
  ASSERT_TRUE(scene.materials[0].rhoTexture);
  ASSERT_EQ(scene.texcoords.size(), scene.positions.size());
  const std::vector<float> halves = patchReflectances(scene, 1.0f);
  ASSERT_EQ(halves.size(), 4u);  // 1 m patches: 2 x 2 over the 2 x 1 quad (its longest edge)
  EXPECT_NEAR(halves[0], 0.0f, 1e-3f);
  EXPECT_NEAR(halves[3], 0.8f, 1e-3f);
  const std::vector<float> whole = patchReflectances(scene, 2.0f);
  ASSERT_EQ(whole.size(), 1u);
  EXPECT_NEAR(whole[0], 0.4f, 2e-3f);
}

TEST(Texture, GltfSamplerAndTextureTransformAreApplied) {
  // The transform maps the quad onto the image's white half: the right patches (u' from 0.75 to
  // 1) 0.8; the left ones (u' from 0.5 to 0.75) border the black half, which the filter of their
  // points (each a quarter of the patch wide, isotropic) reaches into: 0.75 measured.
  const Scene scene = loadScene(kTextured + "quad.gltf");
  ASSERT_TRUE(scene.warnings.empty()) << scene.warnings.front();
  const TextureMap& map = scene.materials[0].rhoTexture;
  ASSERT_TRUE(map);
  EXPECT_EQ(map.wrapU, TextureWrap::ClampToEdge);
  EXPECT_NEAR(map.apply(Vec2(0.0f, 0.3f)).x, 0.5f, 1e-6f);
  EXPECT_NEAR(map.apply(Vec2(1.0f, 0.3f)).x, 1.0f, 1e-6f);
  EXPECT_NEAR(map.apply(Vec2(1.0f, 0.3f)).y, 0.3f, 1e-6f);
  const std::vector<float> rho = patchReflectances(scene, 1.0f);
  ASSERT_EQ(rho.size(), 4u);
  EXPECT_NEAR(rho[2], 0.8f, 2e-3f);
  EXPECT_NEAR(rho[3], 0.8f, 2e-3f);
  EXPECT_GT(rho[0], 0.7f);  // without the transform: 0 (the black half)
}

TEST(Texture, UnusableTexturesFallBackWithAWarning) {
  const fs::path dir = fs::path(::testing::TempDir()) / "radiosity_texture_fallbacks";
  fs::create_directories(dir);
  fs::copy_file(kTextured + "half.png", dir / "half.png", fs::copy_options::overwrite_existing);
  // A missing image: the factor alone, and a warning naming the material.
  std::ofstream(dir / "missing.mtl") << "newmtl stone\nKd 0.6 0.6 0.6\nmap_Kd nowhere.png\n";
  std::ofstream(dir / "missing.obj")
      << "mtllib missing.mtl\nv 0 0 0\nv 0 0 1\nv 1 0 1\nvt 0 0\nvt 0 1\nvt 1 1\nusemtl "
         "stone\nf 1/1 2/2 3/3\n";
  const Scene missing = loadScene((dir / "missing.obj").string());
  ASSERT_EQ(missing.warnings.size(), 1u);
  EXPECT_NE(missing.warnings[0].find("stone"), std::string::npos) << missing.warnings[0];
  EXPECT_FALSE(missing.materials[0].rhoTexture);
  EXPECT_NEAR(missing.materials[0].rho.g, 0.6f, 1e-6f);
  // Faces without texture coordinates: the texture's mean (0.5 here) times the factor.
  std::ofstream(dir / "unmapped.mtl") << "newmtl stone\nKd 0.6 0.6 0.6\nmap_Kd half.png\n";
  std::ofstream(dir / "unmapped.obj")
      << "mtllib unmapped.mtl\nv 0 0 0\nv 0 0 1\nv 1 0 1\nusemtl stone\nf 1 2 3\n";
  const Scene unmapped = loadScene((dir / "unmapped.obj").string());
  ASSERT_EQ(unmapped.warnings.size(), 1u);
  EXPECT_NE(unmapped.warnings[0].find("without texture coordinates"), std::string::npos);
  EXPECT_FALSE(unmapped.materials[0].rhoTexture);
  EXPECT_TRUE(unmapped.texcoords.empty());
  EXPECT_NEAR(unmapped.materials[0].rho.g, 0.3f, 1e-3f);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rad
