// The half-float conversions against F16C, whose bits the voxel method's packed values had
// before they were computed in integers (and still have, on every processor).
#include "voxel/half_float.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#if defined(__x86_64__) || defined(__i386__)
#include <cpuid.h>
#include <immintrin.h>
#endif

namespace rad {
namespace {

#if defined(__x86_64__) || defined(__i386__)
// The processor's own conversions, whatever the flags the test is built with.
[[gnu::target("f16c")]] uint16_t f16cToHalf(float value) {
  return uint16_t(_mm_extract_epi16(_mm_cvtps_ph(_mm_set_ss(value), _MM_FROUND_TO_NEAREST_INT), 0));
}
[[gnu::target("f16c")]] float f16cFromHalf(uint16_t half) {
  return _mm_cvtss_f32(_mm_cvtph_ps(_mm_cvtsi32_si128(half)));
}
bool hasF16c() {
  unsigned a = 0, b = 0, c = 0, d = 0;  // (clang 14's __builtin_cpu_supports knows no "f16c")
  return __get_cpuid(1, &a, &b, &c, &d) && (c & bit_F16C) != 0;
}
#else
uint16_t f16cToHalf(float) {
  return 0;
}
float f16cFromHalf(uint16_t) {
  return 0.0f;
}
bool hasF16c() {
  return false;
}
#endif

uint32_t bitsOf(float f) {
  return std::bit_cast<uint32_t>(f);
}

// Every float the rounding could go wrong on: for each half, the floats at, just around and
// halfway to the next half, at every scale (the subnormal halves' ties lie at other bits than
// the normal ones'), and infinities and NaNs; plus an even spread over all floats.
std::vector<uint32_t> floatsToConvert() {
  std::vector<uint32_t> bits;
  for (uint32_t h = 0; h < 0x10000; ++h) {
    const float at = fromHalf(uint16_t(h));
    if (std::isnan(at) || std::isinf(at)) continue;
    const float next = fromHalf(uint16_t(h + 1));
    const uint32_t b = bitsOf(at);
    for (uint32_t d : {0u, 1u, 2u}) bits.insert(bits.end(), {b + d, b - d});
    // Exact (the halves have 11 bits); past the largest half, halfway to 2^16.
    const uint32_t tie = std::isinf(next) ? b + 0x1000u : bitsOf((at + next) / 2.0f);
    for (uint32_t d : {0u, 1u, 2u}) bits.insert(bits.end(), {tie + d, tie - d});
  }
  for (uint32_t b = 0; b < 0xffff0000u; b += 997) bits.push_back(b);
  for (uint32_t sign : {0u, 0x80000000u})
    for (uint32_t payload : {0u, 1u, 0x1fffu, 0x2000u, 0x400000u, 0x7fffffu})
      bits.push_back(sign | 0x7f800000u | payload);
  return bits;
}

TEST(HalfFloat, ToHalfRoundsAsF16cDoes) {
  if (!hasF16c()) GTEST_SKIP() << "no F16C on this processor";
  size_t wrong = 0;
  for (uint32_t b : floatsToConvert()) {
    const float f = std::bit_cast<float>(b);
    if (toHalf(f) != f16cToHalf(f) && ++wrong <= 10)
      ADD_FAILURE() << std::hex << "float 0x" << b << ": 0x" << toHalf(f) << ", F16C 0x"
                    << f16cToHalf(f);
  }
  EXPECT_EQ(wrong, 0u);
}

TEST(HalfFloat, FromHalfWidensAsF16cDoes) {
  if (!hasF16c()) GTEST_SKIP() << "no F16C on this processor";
  for (uint32_t h = 0; h < 0x10000; ++h)
    ASSERT_EQ(bitsOf(fromHalf(uint16_t(h))), bitsOf(f16cFromHalf(uint16_t(h)))) << std::hex << h;
}

// Without F16C to compare with: the rules themselves.
TEST(HalfFloat, RoundsToNearestTiesToEven) {
  EXPECT_EQ(toHalf(1.0f), 0x3c00);
  EXPECT_EQ(toHalf(1.0f + 0x1p-11f), 0x3c00);  // halfway to the next: to the even one
  EXPECT_EQ(toHalf(1.0f + 3 * 0x1p-11f), 0x3c02);
  EXPECT_EQ(toHalf(65504.0f), 0x7bff);
  EXPECT_EQ(toHalf(65519.0f), 0x7bff);
  EXPECT_EQ(toHalf(65520.0f), 0x7c00);
  EXPECT_EQ(toHalf(std::numeric_limits<float>::infinity()), 0x7c00);
  EXPECT_EQ(toHalf(0x1p-24f), 0x0001);
  EXPECT_EQ(toHalf(0x1p-25f), 0x0000);
  EXPECT_EQ(toHalf(0x1.8p-24f), 0x0002);
  EXPECT_EQ(toHalf(-0x1p-14f), 0x8400);
  EXPECT_EQ(toHalf(std::numeric_limits<float>::quiet_NaN()) & 0x7e00, 0x7e00);
  for (uint32_t h = 0; h < 0x7c00; ++h)
    ASSERT_EQ(toHalf(fromHalf(uint16_t(h))), h) << h;  // every finite half comes back
}

}  // namespace
}  // namespace rad
