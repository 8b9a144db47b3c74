#pragma once
// Sizes computed from numbers a file supplies (counts, offsets, strides) must not wrap: an
// offset near 2^64 plus a length would pass a bounds check and read far outside the buffer.

#include <cstddef>
#include <optional>

namespace rad {

/// a + b, or nothing if it does not fit a size_t.
inline std::optional<size_t> checkedAdd(size_t a, size_t b) {
  size_t sum = 0;
  if (__builtin_add_overflow(a, b, &sum)) return std::nullopt;
  return sum;
}

/// a * b, or nothing if it does not fit a size_t.
inline std::optional<size_t> checkedMultiply(size_t a, size_t b) {
  size_t product = 0;
  if (__builtin_mul_overflow(a, b, &product)) return std::nullopt;
  return product;
}

}  // namespace rad
