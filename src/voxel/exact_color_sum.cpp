#include "voxel/exact_color_sum.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <stdexcept>

namespace rad {

namespace {

constexpr double kLargestCount = 4611686018427387904.0;  // 2^62

// Rounded half away from zero by truncation, which compiles inline (llround is a call).
int64_t countOf(float value, double perUnit) {
  const double units = std::clamp(double(value) * perUnit, -kLargestCount, kLargestCount);
  return int64_t(units + std::copysign(0.5, units));
}

}  // namespace

ExactColorSum::ExactColorSum(size_t size, float unit)
    : counts_(3 * size, 0), perUnit_(1.0 / double(unit)), unit_(unit) {
  int exponent = 0;
  if (!(unit > 0.0f) || std::frexp(unit, &exponent) != 0.5f)
    throw std::invalid_argument("ExactColorSum: the unit must be a positive power of two");
}

void ExactColorSum::add(std::span<const Color> values) {
  assert(3 * values.size() == counts_.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, values.size(), 4096), [&](const auto& r) {
    for (size_t i = r.begin(); i != r.end(); ++i)
      for (int c = 0; c < 3; ++c) counts_[3 * i + size_t(c)] += countOf(values[i][c], perUnit_);
  });
}

void ExactColorSum::sumOverProcesses(const ProcessShare& processes) {
  if (processes.split()) processes.sumIntegers(counts_);
}

void ExactColorSum::store(std::span<Color> out) const {
  assert(3 * out.size() == counts_.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, out.size(), 4096), [&](const auto& r) {
    for (size_t i = r.begin(); i != r.end(); ++i)
      for (int c = 0; c < 3; ++c) out[i][c] = float(double(counts_[3 * i + size_t(c)]) * unit_);
  });
}

}  // namespace rad
