#include <radiosity/image.h>

#include <cmath>

namespace rad {

float srgbEncode(float linear) {
  // IEC 61966-2-1: a linear toe below the threshold, then a 1/2.4 power with offset.
  if (linear < 0.0031308f) return 12.92f * linear;
  return 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

std::array<uint8_t, 3> toneMapPixel(const Color& radiance, float exposureEV) {
  const float scale = std::exp2(exposureEV);
  std::array<uint8_t, 3> out{};
  for (int c = 0; c < 3; ++c) {
    const float linear = radiance[c] * scale;
    // The negated comparison also catches NaN, which must not reach the 8-bit conversion.
    if (!(linear > 0.0f)) {
      out[size_t(c)] = 0;
      continue;
    }
    const float encoded = std::min(srgbEncode(linear), 1.0f);
    out[size_t(c)] = uint8_t(std::lround(encoded * 255.0f));
  }
  return out;
}

}  // namespace rad
