#include "voxel/half_colors.h"

#include <immintrin.h>

#include <cmath>

namespace rad {

float halfScaleFor(float largest) {
  constexpr int kHighest = 14, kLowest = -8;
  if (!(largest > 0.0f) || !std::isfinite(largest)) return 1.0f;
  int exponent = 0;
  std::frexp(largest, &exponent);  // largest = m 2^exponent, 0.5 <= m < 1
  if (exponent - 1 >= kLowest && exponent <= kHighest) return 1.0f;
  return std::ldexp(1.0f, exponent - kHighest);
}

HalfColors::HalfColors(std::span<const Color> colors)
    : bits_(colors.size()),
      scale_(halfScaleFor(largestComponent(colors.size(), [&](size_t i) { return colors[i]; }))) {
  const float inverse = 1.0f / scale_;  // a power of two: exact
  for (size_t i = 0; i < colors.size(); ++i)
    for (int k = 0; k < 3; ++k)
      bits_[i][size_t(k)] = _cvtss_sh(colors[i][k] * inverse, _MM_FROUND_TO_NEAREST_INT);
}

Color HalfColors::operator[](size_t i) const {
  const std::array<uint16_t, 3>& b = bits_[i];
  return Color(_cvtsh_ss(b[0]), _cvtsh_ss(b[1]), _cvtsh_ss(b[2])) * scale_;
}

}  // namespace rad
