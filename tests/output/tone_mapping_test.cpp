#include <gtest/gtest.h>
#include <radiosity/image.h>

#include <cmath>
#include <limits>

namespace {

// Reference values computed by hand from the IEC 61966-2-1 formula:
// srgb(x) = 12.92 x for x < 0.0031308, else 1.055 x^(1/2.4) - 0.055.
TEST(SrgbEncode, MatchesIecFormulaAtKnownPoints) {
  EXPECT_FLOAT_EQ(rad::srgbEncode(0.0f), 0.0f);
  EXPECT_NEAR(rad::srgbEncode(1.0f), 1.0f, 1e-6f);
  // 1.055 * 0.5^(1/2.4) - 0.055 = 1.055 * 0.749154 - 0.055 = 0.735357
  EXPECT_NEAR(rad::srgbEncode(0.5f), 0.735357f, 1e-5f);
  // 18% grey: 1.055 * 0.18^(1/2.4) - 0.055 = 0.461356
  EXPECT_NEAR(rad::srgbEncode(0.18f), 0.461356f, 1e-5f);
  // Linear toe: 12.92 * 0.001 = 0.01292
  EXPECT_NEAR(rad::srgbEncode(0.001f), 0.01292f, 1e-7f);
}

TEST(SrgbEncode, BothSegmentsMeetAtTheThreshold) {
  // 12.92 * 0.0031308 = 0.040450; the power segment gives 0.040449 there (the curve is
  // continuous to 1e-6 by construction of the standard's constants).
  const float below = rad::srgbEncode(std::nextafter(0.0031308f, 0.0f));
  const float at = rad::srgbEncode(0.0031308f);
  EXPECT_NEAR(below, 0.0404500f, 1e-6f);
  EXPECT_NEAR(at, 0.0404500f, 2e-6f);
}

using Rgb = std::array<uint8_t, 3>;

TEST(ToneMapPixel, EndpointsAndMidGrey) {
  EXPECT_EQ(rad::toneMapPixel(rad::Color(0.0f), 0.0f), (Rgb{0, 0, 0}));
  EXPECT_EQ(rad::toneMapPixel(rad::Color(1.0f), 0.0f), (Rgb{255, 255, 255}));
  // 0.735357 * 255 = 187.52 -> 188
  EXPECT_EQ(rad::toneMapPixel(rad::Color(0.5f), 0.0f), (Rgb{188, 188, 188}));
}

TEST(ToneMapPixel, ChannelsAreIndependent) {
  // 0.18 -> 0.461356 * 255 = 117.65 -> 118
  EXPECT_EQ(rad::toneMapPixel(rad::Color(1.0f, 0.18f, 0.0f), 0.0f), (Rgb{255, 118, 0}));
}

TEST(ToneMapPixel, LinearSegmentThreshold) {
  // 0.0031308 -> 0.04045 * 255 = 10.31 -> 10
  EXPECT_EQ(rad::toneMapPixel(rad::Color(0.0031308f), 0.0f)[0], 10);
  // 0.001 -> 0.01292 * 255 = 3.29 -> 3
  EXPECT_EQ(rad::toneMapPixel(rad::Color(0.001f), 0.0f)[0], 3);
}

TEST(ToneMapPixel, ExposureScalesByPowersOfTwo) {
  EXPECT_EQ(rad::toneMapPixel(rad::Color(0.25f), 1.0f), rad::toneMapPixel(rad::Color(0.5f), 0.0f));
  EXPECT_EQ(rad::toneMapPixel(rad::Color(2.0f), -2.0f), rad::toneMapPixel(rad::Color(0.5f), 0.0f));
  // And it is not a no-op: 0.25 at EV 0 is 0.537099 * 255 = 136.96 -> 137.
  EXPECT_EQ(rad::toneMapPixel(rad::Color(0.25f), 0.0f)[0], 137);
}

TEST(ToneMapPixel, OutOfRangeAndNonFiniteValuesClamp) {
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(rad::toneMapPixel(rad::Color(20.7f, 1.0001f, inf), 0.0f), (Rgb{255, 255, 255}));
  EXPECT_EQ(rad::toneMapPixel(rad::Color(-1.0f, nan, -inf), 0.0f), (Rgb{0, 0, 0}));
}

}  // namespace
