#pragma once
// Monte Carlo sampling building blocks. Sources: Shirley and Chiu, "A Low Distortion Map Between
// Disk and Square" (1997) with Malley's method for the cosine hemisphere; Osada et al., "Shape
// Distributions" (2002) for area-uniform triangle points; Duff et al., "Building an Orthonormal
// Basis, Revisited" (JCGT 2017); Vose, "A linear algorithm for generating random numbers with a
// given distribution" (1991) for the alias table.

#include <radiosity/types.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/gtc/constants.hpp>
#include <numeric>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/rng.h"

namespace rad {

/// Maps [0,1)^2 to the unit disk, keeping strata compact (Shirley-Chiu concentric map).
inline Vec2 sampleConcentricDisk(Vec2 u) {
  const Vec2 o = 2.0f * u - Vec2(1.0f);
  if (o.x == 0.0f && o.y == 0.0f) return Vec2(0.0f);
  const float quarterPi = 0.25f * glm::pi<float>();
  float r, theta;
  if (std::abs(o.x) > std::abs(o.y)) {
    r = o.x;
    theta = quarterPi * (o.y / o.x);
  } else {
    r = o.y;
    theta = 2.0f * quarterPi - quarterPi * (o.x / o.y);
  }
  return r * Vec2(std::cos(theta), std::sin(theta));
}

/// A direction about +z with density cos(theta) / pi (Malley: lift a disk point).
inline Vec3 sampleCosineHemisphere(Vec2 u) {
  const Vec2 d = sampleConcentricDisk(u);
  const float z = std::sqrt(std::max(0.0f, 1.0f - d.x * d.x - d.y * d.y));
  return Vec3(d.x, d.y, z);
}

/// Barycentrics (b1, b2) of a point uniform in area on a triangle: p = (1-b1-b2) p0 + b1 p1 + b2
/// p2.
inline Vec2 sampleUniformTriangle(Vec2 u) {
  const float s = std::sqrt(u.x);
  return Vec2(1.0f - s, u.y * s);
}

/// A point uniform in [0,1)^2; draws two numbers from `rng`, y's first: the order GCC gave the
/// former inline `Vec2(rng.uniform(), rng.uniform())` (unspecified in C++), kept so that results
/// stay the same and no longer depend on the compiler.
inline Vec2 uniformSquare(Rng& rng) {
  const float y = rng.uniform();
  const float x = rng.uniform();
  return Vec2(x, y);
}

/// Cells per side of the smallest square grid of at least `count` strata (at least 1).
inline int strataPerSide(int count) {
  return std::max(1, int(std::ceil(std::sqrt(double(count)))));
}

/// A point uniform in cell `stratum` (row-major: x = stratum % side) of the side x side grid
/// over [0,1)^2; draws two numbers from `rng`. Jittered (stratified) sampling of the square, and
/// through an area-preserving map (sampleUniformTriangle, PatchMesh::samplePoint) of a triangle.
inline Vec2 sampleStratum(int stratum, int side, Rng& rng) {
  const Vec2 jitter = uniformSquare(rng);
  return Vec2((float(stratum % side) + jitter.x) / float(side),
              (float(stratum / side) + jitter.y) / float(side));
}

/// Sample `index` of `count` over [0,1)^2: the first side^2 (side = floor(sqrt(count))) lie one
/// in each cell of a side x side grid, jittered, and any others anywhere, so that every count is
/// unbiased and a square one fully stratified. Draws two numbers from `rng`.
inline Vec2 stratifiedSample(int index, int count, Rng& rng) {
  const int side = std::max(1, int(std::sqrt(double(count))));
  return index < side * side ? sampleStratum(index, side, rng) : uniformSquare(rng);
}

/// Sample `index` of `count` over a pixel: one sample lies at the centre; more are
/// stratifiedSample's (at 4 samples an edge's pixels take 0, 1/4, ... 1 of each side instead of
/// a random share).
inline Vec2 pixelSample(int index, int count, Rng& rng) {
  return count <= 1 ? Vec2(0.5f) : stratifiedSample(index, count, rng);
}

/// A uniformly random permutation of 0 .. n-1 (Fisher-Yates), e.g. to pair the strata of two
/// stratified sample sets; draws n - 1 numbers from `rng`.
inline std::vector<int> randomPermutation(int n, Rng& rng) {
  std::vector<int> p(static_cast<size_t>(std::max(n, 0)));
  std::iota(p.begin(), p.end(), 0);
  for (int k = n - 1; k > 0; --k) std::swap(p[k], p[rng.next() % uint32_t(k + 1)]);
  return p;
}

/// Completes the unit vector n to a right-handed orthonormal frame (t, b, n) without branches
/// that lose precision near the poles.
inline void orthonormalBasis(const Vec3& n, Vec3& t, Vec3& b) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float c = n.x * n.y * a;
  t = Vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = Vec3(c, sign + n.y * n.y * a, -n.y);
}

/// Expresses a direction given about +z in the frame whose third axis is n.
inline Vec3 toWorld(const Vec3& local, const Vec3& n) {
  Vec3 t, b;
  orthonormalBasis(n, t, b);
  return local.x * t + local.y * b + local.z * n;
}

/// Picks index i with probability weights[i] / sum(weights) in O(1) (Vose's alias table).
class DiscreteDistribution {
 public:
  DiscreteDistribution() = default;
  /// Weights must be finite and non-negative; throws std::invalid_argument if all are zero.
  explicit DiscreteDistribution(std::span<const double> weights) { build(weights); }

  bool empty() const { return pmf_.empty(); }
  size_t size() const { return pmf_.size(); }
  double total() const { return total_; }
  double pmf(size_t i) const { return pmf_[i]; }

  /// One uniform number in [0, 1) gives the index.
  size_t sample(float u) const {
    const double scaled = double(u) * double(pmf_.size());
    const size_t i = std::min(size_t(scaled), pmf_.size() - 1);
    return (scaled - double(i)) < probability_[i] ? i : alias_[i];
  }

 private:
  void build(std::span<const double> weights) {
    total_ = std::accumulate(weights.begin(), weights.end(), 0.0);
    if (!(total_ > 0.0) || !std::isfinite(total_))
      throw std::invalid_argument("DiscreteDistribution: weights must have a positive sum");
    const size_t n = weights.size();
    pmf_.resize(n);
    probability_.assign(n, 1.0);
    alias_.resize(n);
    std::vector<double> scaled(n);
    std::vector<size_t> small, large;
    for (size_t i = 0; i < n; ++i) {
      pmf_[i] = weights[i] / total_;
      scaled[i] = pmf_[i] * double(n);
      alias_[i] = i;
      (scaled[i] < 1.0 ? small : large).push_back(i);
    }
    while (!small.empty() && !large.empty()) {
      const size_t s = small.back(), l = large.back();
      small.pop_back();
      probability_[s] = scaled[s];
      alias_[s] = l;
      scaled[l] -= 1.0 - scaled[s];
      if (scaled[l] < 1.0) {
        large.pop_back();
        small.push_back(l);
      }
    }
    // Leftovers are 1 up to rounding: they keep probability 1 and alias themselves.
  }

  std::vector<double> pmf_, probability_;
  std::vector<size_t> alias_;
  double total_ = 0.0;
};

}  // namespace rad
