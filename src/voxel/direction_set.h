#pragma once
// The discrete directions of the voxel method: the surface of a digital ball.
//
// Based on: P. Chatelier and R. Malgouyres, "A low-complexity discrete radiosity method",
// Computers & Graphics 30(1), 2006, section 3: the directions are the voxels v of the digital ball
// x^2 + y^2 + z^2 <= R^2 that have a face-neighbour outside it (R = 38 gives 14,790); the factor of
// v is the solid angle, seen from the centre, of the faces of v's unit cube that border the
// outside. Those faces form a closed surface around the centre, so the factors sum to 4 pi.

#include <radiosity/types.h>

#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

namespace rad {

using IVec3 = glm::ivec3;

struct DiscreteDirection {
  IVec3 step;         ///< primitive integer direction (components divided by their gcd)
  Vec3d unit;         ///< step normalized
  double solidAngle;  ///< the direction's factor, in steradians
};

class DirectionSet {
 public:
  /// All directions of the digital sphere of radius `radius` (>= 1).
  explicit DirectionSet(int radius);

  int radius() const { return radius_; }
  size_t size() const { return directions_.size(); }
  const DiscreteDirection& operator[](size_t i) const { return directions_[i]; }
  /// Directions come in opposite pairs: pair k is (first(k), its opposite), k < size() / 2.
  /// Sweeping a line in one order serves the first, the reverse order serves the opposite.
  const DiscreteDirection& pairFirst(size_t k) const { return directions_[pairs_[k]]; }
  size_t pairCount() const { return pairs_.size(); }
  double totalSolidAngle() const;

 private:
  int radius_;
  std::vector<DiscreteDirection> directions_;
  std::vector<uint32_t> pairs_;
};

/// Solid angle of the axis-aligned rectangle [u0,u1] x [v0,v1] in the plane at distance
/// `depth` > 0 along the remaining axis, seen from the origin (exact).
double rectangleSolidAngle(double u0, double u1, double v0, double v1, double depth);

}  // namespace rad
