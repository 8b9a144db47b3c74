// ExactColorSum: the same bits whatever the order and grouping of its terms, which float sums
// do not give, and within one count of the true sum.
#include "voxel/exact_color_sum.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

namespace rad {
namespace {

// Terms spread over nine decades, the way a bright and a dim side's light differ.
std::vector<std::vector<Color>> randomTerms(size_t count, size_t size) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> mantissa(0.5f, 1.0f);
  std::uniform_int_distribution<int> exponent(-30, 0);
  std::vector<std::vector<Color>> terms(count, std::vector<Color>(size));
  for (auto& term : terms)
    for (Color& c : term)
      for (int k = 0; k < 3; ++k) c[k] = std::ldexp(mantissa(rng), exponent(rng));
  return terms;
}

TEST(ExactColorSum, AnyOrderAndGroupingGivesTheSameBits) {
  const size_t size = 64;
  const std::vector<std::vector<Color>> terms = randomTerms(200, size);
  const float unit = std::ldexp(1.0f, -58);
  ExactColorSum forward(size, unit);
  for (const auto& t : terms) forward.add(t);
  // Backward, and as three parts summed apart and then added (as three processes would).
  ExactColorSum backward(size, unit);
  for (auto it = terms.rbegin(); it != terms.rend(); ++it) backward.add(*it);
  std::vector<ExactColorSum> parts(3, ExactColorSum(size, unit));
  for (size_t k = 0; k < terms.size(); ++k) parts[(k * 7) % 3].add(terms[k]);
  std::vector<Color> a(size), b(size), partSums(size);
  forward.store(a);
  backward.store(b);
  EXPECT_EQ(a, b);
  // The parts added as a split run adds them: the last "process" ends with the others' counts
  // added to its own.
  std::vector<std::vector<int64_t>> seen;
  ProcessShare three;
  three.count = 3;
  three.sumIntegers = [&](std::span<int64_t> counts) {
    seen.emplace_back(counts.begin(), counts.end());
    if (seen.size() < 3) return;
    for (size_t p = 0; p < 2; ++p)
      for (size_t i = 0; i < counts.size(); ++i) counts[i] += seen[p][i];
  };
  for (ExactColorSum& part : parts) part.sumOverProcesses(three);
  parts[2].store(partSums);
  EXPECT_EQ(a, partSums);
  // Float sums of the same terms in the two orders differ somewhere: what the class is for.
  std::vector<Color> floatForward(size, Color(0.0f)), floatBackward(size, Color(0.0f));
  for (const auto& t : terms)
    for (size_t i = 0; i < size; ++i) floatForward[i] += t[i];
  for (auto it = terms.rbegin(); it != terms.rend(); ++it)
    for (size_t i = 0; i < size; ++i) floatBackward[i] += (*it)[i];
  EXPECT_NE(floatForward, floatBackward);
  // Against the sum in doubles: the counts round by half a unit (2^-59) a term, nothing next to
  // the float the sum is stored in (6e-8 of it), hence 1e-7.
  for (size_t i = 0; i < size; ++i)
    for (int k = 0; k < 3; ++k) {
      double exact = 0.0;
      for (const auto& t : terms) exact += t[i][k];
      EXPECT_NEAR(a[i][k], exact, 1e-7 * exact);
    }
}

TEST(ExactColorSum, RefusesAUnitThatIsNotAPowerOfTwo) {
  EXPECT_THROW(ExactColorSum(4, 0.3f), std::invalid_argument);
  EXPECT_THROW(ExactColorSum(4, 0.0f), std::invalid_argument);
  EXPECT_NO_THROW(ExactColorSum(4, 0.25f));
}

}  // namespace
}  // namespace rad
