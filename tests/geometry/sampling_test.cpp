// Moments of the sampling routines against their closed forms.
#include "geometry/sampling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "core/rng.h"

namespace rad {
namespace {

constexpr int kSamples = 200000;

TEST(Sampling, CosineHemisphereMoments) {
  // For density cos(theta)/pi on the hemisphere E[cos^k] = 2/(k+2): E[z] = 2/3, E[z^2] = 1/2;
  // x and y are symmetric, so their means vanish. Standard errors are below 1e-3.
  Rng rng(1, 0);
  double z1 = 0, z2 = 0, x = 0, y = 0;
  for (int i = 0; i < kSamples; ++i) {
    const Vec3 d = sampleCosineHemisphere({rng.uniform(), rng.uniform()});
    ASSERT_NEAR(glm::length(d), 1.0f, 1e-5f);
    ASSERT_GE(d.z, 0.0f);
    z1 += d.z, z2 += d.z * d.z, x += d.x, y += d.y;
  }
  EXPECT_NEAR(z1 / kSamples, 2.0 / 3.0, 4e-3);
  EXPECT_NEAR(z2 / kSamples, 0.5, 4e-3);
  EXPECT_NEAR(x / kSamples, 0.0, 5e-3);
  EXPECT_NEAR(y / kSamples, 0.0, 5e-3);
}

TEST(Sampling, ConcentricDiskIsUniform) {
  // Uniform on the unit disk: E[r^2] = 1/2, and a quarter of the points in each quadrant.
  Rng rng(2, 0);
  double r2 = 0;
  std::array<int, 4> quadrant{};
  for (int i = 0; i < kSamples; ++i) {
    const Vec2 p = sampleConcentricDisk({rng.uniform(), rng.uniform()});
    ASSERT_LE(glm::dot(p, p), 1.0f + 1e-6f);
    r2 += glm::dot(p, p);
    ++quadrant[(p.x >= 0 ? 1 : 0) + (p.y >= 0 ? 2 : 0)];
  }
  EXPECT_NEAR(r2 / kSamples, 0.5, 4e-3);
  for (int q : quadrant) EXPECT_NEAR(double(q) / kSamples, 0.25, 5e-3);
}

TEST(Sampling, UniformTriangleMoments) {
  // Area-uniform barycentrics follow Dirichlet(1,1,1): E[b] = 1/3, E[b^2] = 1/6, and the
  // medial triangle (corner weights all <= 1/2) holds a quarter of the area.
  Rng rng(3, 0);
  std::array<double, 3> mean{}, square{};
  int medial = 0;
  for (int i = 0; i < kSamples; ++i) {
    const Vec2 b = sampleUniformTriangle({rng.uniform(), rng.uniform()});
    const std::array<double, 3> w{1.0 - b.x - b.y, b.x, b.y};
    for (int k = 0; k < 3; ++k) {
      ASSERT_GE(w[k], -1e-6);
      mean[k] += w[k], square[k] += w[k] * w[k];
    }
    medial += (w[0] <= 0.5 && w[1] <= 0.5 && w[2] <= 0.5) ? 1 : 0;
  }
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(mean[k] / kSamples, 1.0 / 3.0, 3e-3) << k;
    EXPECT_NEAR(square[k] / kSamples, 1.0 / 6.0, 3e-3) << k;
  }
  EXPECT_NEAR(double(medial) / kSamples, 0.25, 5e-3);
}

TEST(Sampling, StrataCoverTheSquareOncePerCell) {
  // The smallest square grid of at least `count` cells, and one point inside each cell.
  EXPECT_EQ(strataPerSide(0), 1);
  EXPECT_EQ(strataPerSide(1), 1);
  EXPECT_EQ(strataPerSide(16), 4);
  EXPECT_EQ(strataPerSide(17), 5);
  Rng rng(6, 0);
  const int side = strataPerSide(37);
  for (int s = 0; s < side * side; ++s) {
    const Vec2 u = sampleStratum(s, side, rng);
    EXPECT_EQ(int(u.x * float(side)), s % side) << s;
    EXPECT_EQ(int(u.y * float(side)), s / side) << s;
  }
  // A permutation pairs the strata of two sets: every index exactly once.
  std::vector<int> p = randomPermutation(side * side, rng);
  std::sort(p.begin(), p.end());
  for (int k = 0; k < side * side; ++k) EXPECT_EQ(p[size_t(k)], k);
}

TEST(Sampling, PixelSamplesAreStratifiedWhereTheCountAllows) {
  Rng rng(7, 0);
  EXPECT_EQ(pixelSample(0, 1, rng), Vec2(0.5f));  // one ray: the pixel's centre
  // 4, 9 and 16 samples: one in each cell of the 2x2, 3x3 and 4x4 grids. 6: one in each quarter,
  // two anywhere. The mean of many pixels' samples is the pixel's centre for every count.
  for (const int count : {4, 6, 9, 16}) {
    const int side = count == 6 ? 2 : int(std::lround(std::sqrt(count)));
    Vec2 mean(0.0f);
    constexpr int kPixels = 20000;
    for (int pixel = 0; pixel < kPixels; ++pixel) {
      std::vector<int> perCell(size_t(side * side), 0);
      for (int s = 0; s < count; ++s) {
        const Vec2 u = pixelSample(s, count, rng);
        ASSERT_TRUE(u.x >= 0.0f && u.x < 1.0f && u.y >= 0.0f && u.y < 1.0f);
        const int cell = int(u.x * float(side)) + side * int(u.y * float(side));
        if (s < side * side) ++perCell[size_t(cell)];
        mean += u;
      }
      for (const int n : perCell) ASSERT_EQ(n, 1) << count;
    }
    mean /= float(kPixels * count);
    EXPECT_NEAR(mean.x, 0.5f, 2e-3f) << count;
    EXPECT_NEAR(mean.y, 0.5f, 2e-3f) << count;
  }
}

TEST(Sampling, OrthonormalBasisIsRightHanded) {
  Rng rng(4, 0);
  std::vector<Vec3> normals{{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, -1, 0}};
  for (int i = 0; i < 1000; ++i) {
    const Vec3 d = sampleCosineHemisphere({rng.uniform(), rng.uniform()});
    normals.push_back(rng.uniform() < 0.5f ? d : -d);
  }
  for (const Vec3& n : normals) {
    Vec3 t, b;
    orthonormalBasis(n, t, b);
    EXPECT_NEAR(glm::length(t), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::length(b), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(t, n), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(b, n), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(t, b), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(glm::cross(t, b) - n), 0.0f, 1e-5f);
  }
}

TEST(Sampling, DiscreteDistributionFrequencies) {
  const std::vector<double> weights{1, 2, 3, 0, 4};
  const DiscreteDistribution d(weights);
  EXPECT_DOUBLE_EQ(d.total(), 10.0);
  Rng rng(5, 0);
  std::array<int, 5> count{};
  for (int i = 0; i < kSamples; ++i) ++count[d.sample(rng.uniform())];
  EXPECT_EQ(count[3], 0);  // zero weight is never chosen
  for (size_t i = 0; i < weights.size(); ++i) {
    const double p = weights[i] / 10.0;
    EXPECT_DOUBLE_EQ(d.pmf(i), p);
    // Binomial standard error sqrt(p(1-p)/n) < 1.2e-3; allow 4 of them.
    EXPECT_NEAR(double(count[i]) / kSamples, p, 5e-3) << i;
  }
}

TEST(Sampling, DiscreteDistributionRejectsZeroWeights) {
  const std::vector<double> zeros{0, 0};
  EXPECT_THROW(DiscreteDistribution{zeros}, std::invalid_argument);
}

}  // namespace
}  // namespace rad
