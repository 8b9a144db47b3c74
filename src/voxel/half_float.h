#pragma once
// One float to a half float and back, for the voxel method's packed values (radiosities, areas,
// weights), bit for bit as F16C's conversions give them (rounding to nearest, ties to even; a
// NaN quieted with its payload's top bits) on any processor. In integers: no instruction set,
// no floating-point environment (flush-to-zero, rounding mode) can change them. The sweep's
// hot loop widens its half floats with Highway instead (sweep_kernels-inl.h); these run once per
// side and iteration. Highway 1.0.3's DemoteTo to float16 truncates where F16C is missing.

#include <bit>
#include <cstdint>

namespace rad {

constexpr uint16_t toHalf(float value) {
  const uint32_t bits = std::bit_cast<uint32_t>(value);
  const auto sign = uint16_t(bits >> 16 & 0x8000u);
  const uint32_t magnitude = bits & 0x7fffffffu;
  const uint32_t exponent = magnitude >> 23;
  if (exponent == 0xff) {  // infinity, or a NaN: quieted, its payload's top 10 bits kept
    const uint32_t payload = magnitude & 0x7fffffu;
    return uint16_t(sign | 0x7c00u | (payload != 0 ? 0x200u | payload >> 13 : 0u));
  }
  if (magnitude >= 0x47800000u) return uint16_t(sign | 0x7c00u);  // 2^16 and up: infinity
  if (exponent >= 113) {
    // A normal half: rebias the exponent (127 to 15) and round the 13 bits dropped to even.
    // A carry out of the mantissa steps the exponent, up to infinity from 65,520 on.
    const uint32_t rounded = magnitude + 0xfffu + (magnitude >> 13 & 1u);
    return uint16_t(sign | (rounded - (112u << 23)) >> 13);
  }
  // Below 2^-14: a subnormal half, a count of 2^-24, rounded to even (2^-25 and below: zero; a
  // count of 1024 is the smallest normal half, which the bits then read as).
  if (exponent < 102) return sign;
  const uint32_t mantissa = (magnitude & 0x7fffffu) | 0x800000u;
  const uint32_t shift = 126 - exponent;  // 14 to 24
  const uint32_t count = mantissa >> shift, rest = mantissa & ((1u << shift) - 1);
  const uint32_t half = 1u << (shift - 1);
  return uint16_t(sign | (count + (rest > half || (rest == half && (count & 1u)))));
}

constexpr float fromHalf(uint16_t half) {
  const uint32_t sign = uint32_t(half & 0x8000u) << 16;
  const uint32_t exponent = half >> 10 & 0x1fu, mantissa = half & 0x3ffu;
  if (exponent == 0x1f)  // infinity, or a NaN, quieted
    return std::bit_cast<float>(sign | 0x7f800000u | mantissa << 13 |
                                (mantissa != 0 ? 0x400000u : 0u));
  if (exponent == 0) {  // zero or subnormal: a count of 2^-24, exact in a float
    const float magnitude = float(mantissa) * 0x1p-24f;
    return std::bit_cast<float>(sign | std::bit_cast<uint32_t>(magnitude));
  }
  return std::bit_cast<float>(sign | (exponent + 112u) << 23 | mantissa << 13);
}

}  // namespace rad
