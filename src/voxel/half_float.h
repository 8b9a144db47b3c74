#pragma once
// One float to a half float and back (F16C), for the voxel method's packed values. Through the
// vector conversion: clang's scalar _cvtss_sh is a macro built on a C99 compound literal.

#include <immintrin.h>

#include <cstdint>

namespace rad {

inline uint16_t toHalf(float value) {
  return uint16_t(_mm_extract_epi16(_mm_cvtps_ph(_mm_set_ss(value), _MM_FROUND_TO_NEAREST_INT), 0));
}

inline float fromHalf(uint16_t half) {
  return _cvtsh_ss(half);
}

}  // namespace rad
