#include "voxel/half_colors.h"

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

}  // namespace rad
