#include <gtest/gtest.h>
#include <radiosity/error.h>
#include <radiosity/image.h>

// stb_image's implementation lives here only, static, so it cannot clash with a copy that the
// library's glTF loader may compile in.
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb/stb_image.h>
#pragma GCC diagnostic pop

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

class ImageFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) / (std::string("image_file_") + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  size_t entries() const {
    return size_t(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()));
  }

  fs::path dir_;
};

// A small non-square image whose every pixel and channel differ, so that a swapped axis,
// flipped row order or channel mix-up changes some value.
rad::Image gradient(int w, int h) {
  rad::Image image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      image.at(x, y) = rad::Color(0.1f * float(x) + 0.013f, 0.37f * float(y) + 0.002f,
                                  float(x * h + y) * 1.7f + 0.5f);
  return image;
}

std::vector<char> readBytes(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const std::string& file, const std::vector<char>& bytes) {
  std::ofstream(file, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

// ---------------------------------------------------------------------------------------- EXR

TEST_F(ImageFileTest, ExrFloatRoundTripIsExact) {
  rad::Image image = gradient(7, 5);
  image.at(3, 2) = rad::Color(1e-20f, 3.4e38f, -0.0f);  // extremes a half could not hold
  rad::writeImage(path("a.exr"), image, {0.0f, rad::ExrPixelType::Float});
  const rad::Image back = rad::readImage(path("a.exr"));
  ASSERT_EQ(back.width, 7);
  ASSERT_EQ(back.height, 5);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(back.pixels[i][c], image.pixels[i][c]) << i << " " << c;
  EXPECT_EQ(entries(), 1u);
}

TEST_F(ImageFileTest, ExrHalfRoundTripWithinHalfPrecision) {
  rad::Image image = gradient(6, 4);
  image.at(0, 0) = rad::Color(20.7f, 1.0f, 0.25f);
  rad::writeImage(path("h.exr"), image);  // half is the default
  const rad::Image back = rad::readImage(path("h.exr"));
  ASSERT_EQ(back.width, 6);
  ASSERT_EQ(back.height, 4);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      // half has an 11-bit significand: relative rounding error <= 2^-11 = 4.9e-4.
      const float expected = image.pixels[i][c];
      ASSERT_NEAR(back.pixels[i][c], expected, 1e-3f * std::abs(expected)) << i << " " << c;
    }
  // 20.7 is not a half: the nearest one is 20.703125 (spacing 2^-6 in [16, 32)).
  EXPECT_EQ(back.at(0, 0).r, 20.703125f);
}

TEST_F(ImageFileTest, ExrHalfIsSmallerThanFloat) {
  const rad::Image image = gradient(32, 32);
  rad::writeImage(path("h.exr"), image, {0.0f, rad::ExrPixelType::Half});
  rad::writeImage(path("f.exr"), image, {0.0f, rad::ExrPixelType::Float});
  EXPECT_LT(fs::file_size(path("h.exr")), fs::file_size(path("f.exr")));
}

TEST_F(ImageFileTest, TruncatedExrIsInputError) {
  rad::writeImage(path("t.exr"), gradient(64, 64), {0.0f, rad::ExrPixelType::Float});
  std::vector<char> bytes = readBytes(path("t.exr"));
  for (size_t keep : {bytes.size() / 2, size_t(40), size_t(3)}) {
    SCOPED_TRACE(keep);
    writeBytes(path("cut.exr"), std::vector<char>(bytes.begin(), bytes.begin() + long(keep)));
    EXPECT_THROW(rad::readImage(path("cut.exr")), rad::InputError);
  }
}

// ---------------------------------------------------------------------------------------- PFM

TEST_F(ImageFileTest, PfmRoundTripIsExact) {
  const rad::Image image = gradient(5, 3);
  rad::writeImage(path("a.pfm"), image);
  const rad::Image back = rad::readImage(path("a.pfm"));
  ASSERT_EQ(back.width, 5);
  ASSERT_EQ(back.height, 3);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(back.pixels[i][c], image.pixels[i][c]);
}

TEST_F(ImageFileTest, PfmLayoutIsLittleEndianBottomRowFirst) {
  // Independent of our reader: decode the bytes by the format's definition.
  rad::Image image(2, 2);
  image.at(0, 0) = rad::Color(1.0f, 2.0f, 3.0f);  // top-left
  image.at(0, 1) = rad::Color(7.0f, 8.0f, 9.0f);  // bottom-left
  rad::writeImage(path("o.pfm"), image);
  const std::vector<char> bytes = readBytes(path("o.pfm"));
  const std::string header = "PF\n2 2\n-1.0\n";
  ASSERT_EQ(bytes.size(), header.size() + 2 * 2 * 3 * 4);
  EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + long(header.size())), header);
  // The first stored pixel is the bottom-left one; 7.0f is 0x40e00000, little-endian.
  const unsigned char first[4] = {0x00, 0x00, 0xe0, 0x40};
  EXPECT_EQ(std::memcmp(bytes.data() + header.size(), first, 4), 0);
  // And reading back keeps the top row on top.
  const rad::Image back = rad::readImage(path("o.pfm"));
  EXPECT_EQ(back.at(0, 0), rad::Color(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(back.at(0, 1), rad::Color(7.0f, 8.0f, 9.0f));
}

TEST_F(ImageFileTest, PfmReaderHandlesBigEndianAndGrey) {
  // Hand-built: a 1 x 2 big-endian grey map, bottom value 2.0f (0x40000000), top 0.5f
  // (0x3f000000).
  std::string file = "Pf\n1 2\n1.0\n";
  file += std::string("\x40\x00\x00\x00", 4) + std::string("\x3f\x00\x00\x00", 4);
  writeBytes(path("g.pfm"), std::vector<char>(file.begin(), file.end()));
  const rad::Image back = rad::readImage(path("g.pfm"));
  ASSERT_EQ(back.width, 1);
  ASSERT_EQ(back.height, 2);
  EXPECT_EQ(back.at(0, 0), rad::Color(0.5f));
  EXPECT_EQ(back.at(0, 1), rad::Color(2.0f));
}

TEST_F(ImageFileTest, MalformedPfmIsInputErrorNamingTheFile) {
  rad::writeImage(path("ok.pfm"), gradient(4, 4));
  const std::vector<char> good = readBytes(path("ok.pfm"));
  const std::vector<std::string> bad = {
      std::string(good.begin(), good.end() - 1),     // truncated pixels
      std::string(good.begin(), good.end()) + "xx",  // trailing garbage
      "PF\n4 4\n",                                   // header cut before the scale
      "P6\n4 4\n255\n",                              // a PPM, not a PFM
      "PF\n-4 4\n-1.0\n",                            // negative width
      "PF\n4 0\n-1.0\n",                             // zero height
      "PF\n4 4\nabc\n",                              // scale not a number
      "PF\n99999 99999\n-1.0\n",                     // absurd size, no data
      "",                                            // empty file
  };
  for (size_t i = 0; i < bad.size(); ++i) {
    SCOPED_TRACE(i);
    writeBytes(path("bad.pfm"), std::vector<char>(bad[i].begin(), bad[i].end()));
    try {
      rad::readImage(path("bad.pfm"));
      ADD_FAILURE() << "expected InputError";
    } catch (const rad::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("bad.pfm"), std::string::npos) << e.what();
    }
  }
}

// ---------------------------------------------------------------------------------------- PNG

TEST_F(ImageFileTest, PngHoldsToneMappedValues) {
  // Expected bytes from the IEC 61966-2-1 formula (see tone_mapping_test.cpp):
  // 0 -> 0, 1 -> 255, 0.5 -> 187.52 -> 188, 0.0031308 -> 10.31 -> 10, 20.7 -> clamped 255.
  rad::Image image(3, 2);
  image.at(0, 0) = rad::Color(0.0f, 1.0f, 0.5f);
  image.at(1, 0) = rad::Color(0.0031308f, 20.7f, 0.25f);
  image.at(2, 0) = rad::Color(0.5f, 0.5f, 0.5f);
  image.at(0, 1) = rad::Color(1.0f, 0.0f, 0.0f);  // bottom row: catches a vertical flip
  rad::writeImage(path("t.png"), image);

  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(path("t.png").c_str(), &w, &h, &n, 3);
  ASSERT_NE(data, nullptr) << stbi_failure_reason();
  ASSERT_EQ(w, 3);
  ASSERT_EQ(h, 2);
  auto px = [&](int x, int y, int c) { return int(data[(y * w + x) * 3 + c]); };
  EXPECT_EQ(px(0, 0, 0), 0);
  EXPECT_EQ(px(0, 0, 1), 255);
  EXPECT_EQ(px(0, 0, 2), 188);
  EXPECT_EQ(px(1, 0, 0), 10);
  EXPECT_EQ(px(1, 0, 1), 255);
  EXPECT_EQ(px(1, 0, 2), 137);  // 0.537099 * 255 = 136.96
  EXPECT_EQ(px(0, 1, 0), 255);
  EXPECT_EQ(px(0, 1, 1), 0);
  stbi_image_free(data);
}

TEST_F(ImageFileTest, PngExposureDoublesTheLinearInput) {
  rad::Image quarter(1, 1);
  quarter.at(0, 0) = rad::Color(0.25f);
  rad::writeImage(path("ev1.png"), quarter, {1.0f, rad::ExrPixelType::Half});
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(path("ev1.png").c_str(), &w, &h, &n, 3);
  ASSERT_NE(data, nullptr);
  EXPECT_EQ(int(data[0]), 188);  // == 0.5 at EV 0
  stbi_image_free(data);
}

// ------------------------------------------------------------------------------ dispatch/errors

TEST_F(ImageFileTest, ExtensionIsCaseInsensitive) {
  EXPECT_TRUE(rad::isSupportedImageFormat("a.PNG"));
  EXPECT_TRUE(rad::isSupportedImageFormat("dir.x/a.Exr"));
  EXPECT_TRUE(rad::isSupportedImageFormat("a.pfm"));
  EXPECT_FALSE(rad::isSupportedImageFormat("a.jpg"));
  EXPECT_FALSE(rad::isSupportedImageFormat("png"));
  rad::writeImage(path("UP.PFM"), gradient(2, 2));
  EXPECT_EQ(rad::readImage(path("UP.PFM")).width, 2);
}

TEST_F(ImageFileTest, UnsupportedExtensionIsInputErrorAndCreatesNothing) {
  try {
    rad::writeImage(path("out.jpg"), gradient(2, 2));
    FAIL() << "expected InputError";
  } catch (const rad::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(".jpg"), std::string::npos) << what;
    for (const char* ext : {".png", ".exr", ".pfm"})
      EXPECT_NE(what.find(ext), std::string::npos) << what;
  }
  EXPECT_EQ(entries(), 0u);
}

TEST_F(ImageFileTest, WritingIntoMissingDirectoryThrowsAndLeavesNothing) {
  for (const char* name : {"missing/a.png", "missing/a.exr", "missing/a.pfm"}) {
    SCOPED_TRACE(name);
    EXPECT_THROW(rad::writeImage(path(name), gradient(2, 2)), std::runtime_error);
  }
  EXPECT_EQ(entries(), 0u);
}

TEST_F(ImageFileTest, EveryFormatLeavesOnlyTheTarget) {
  for (const char* name : {"a.png", "a.exr", "a.pfm"}) rad::writeImage(path(name), gradient(3, 3));
  EXPECT_EQ(entries(), 3u);
}

TEST_F(ImageFileTest, ReadingMissingFileIsInputError) {
  for (const char* name : {"none.exr", "none.pfm"}) {
    try {
      rad::readImage(path(name));
      ADD_FAILURE() << "expected InputError";
    } catch (const rad::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(rad::readImage(path("a.png")), rad::InputError);
}

}  // namespace
