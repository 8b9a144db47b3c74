// False-colour pictures (false_colour.h): the ramp's colours where the values are, isolines at
// the legend's steps, the legend beside the picture.
#include <gtest/gtest.h>
#include <radiosity/false_colour.h>

#include <array>
#include <cmath>

namespace rad {
namespace {

TEST(FalseColour, StepsAreOneTwoOrFiveTimesAPowerOfTen) {
  EXPECT_DOUBLE_EQ(falseColourStep(1000.0), 200.0);
  EXPECT_DOUBLE_EQ(falseColourStep(37.0), 10.0);
  EXPECT_DOUBLE_EQ(falseColourStep(0.3), 0.1);
  EXPECT_DOUBLE_EQ(falseColourStep(5.0), 1.0);
  EXPECT_DOUBLE_EQ(falseColourStep(2400.0), 500.0);
  EXPECT_DOUBLE_EQ(falseColourStep(0.0), 1.0);
}

// A ramp of 0 to 990 lx across 100 pixels (luminance x from 0 to 99, 10 lx each) under a top of
// 1,000 lx: steps of 200 lx, so isolines where the value passes 200, 400, 600 and 800.
TEST(FalseColour, ColoursFollowTheRampAndIsolinesTheSteps) {
  Image irradiance(100, 10);
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 100; ++x) irradiance.at(x, y) = Color(float(x));
  const Image picture = falseColourPicture(irradiance, {10.0, "lx", 1000.0});
  ASSERT_EQ(picture.height, 10);
  ASSERT_GT(picture.width, 100);  // the legend's strip
  // 100 lx is 0.1 of the ramp: 0.6 of the way from its first stop #30123b to its second
  // #4686fb (the viewer's Turbo-like stops, web/viewer.js), in sRGB as the PNG shows it.
  const std::array<uint8_t, 3> shown = toneMapPixel(picture.at(10, 5), 0.0f);
  const double expected[3] = {0x30 + 0.6 * (0x46 - 0x30), 0x12 + 0.6 * (0x86 - 0x12),
                              0x3b + 0.6 * (0xfb - 0x3b)};
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(shown[size_t(c)], expected[c], 1.0) << c;
  // The isolines: dark where the next pixel lies in another step, nowhere else in the row.
  int lines = 0;
  for (int x = 0; x < 100; ++x) {
    const std::array<uint8_t, 3> p = toneMapPixel(picture.at(x, 5), 0.0f);
    const bool dark = p[0] < 30 && p[1] < 30 && p[2] < 30;  // the ramp's darkest is (48, 18, 59)
    EXPECT_EQ(dark, x == 19 || x == 39 || x == 59 || x == 79) << x;
    lines += dark ? 1 : 0;
  }
  EXPECT_EQ(lines, 4);
  // The legend writes its labels in white.
  int white = 0;
  for (int y = 0; y < picture.height; ++y)
    for (int x = 100; x < picture.width; ++x)
      white += toneMapPixel(picture.at(x, y), 0.0f)[0] == 255 ? 1 : 0;
  EXPECT_GT(white, 0);
}

}  // namespace
}  // namespace rad
