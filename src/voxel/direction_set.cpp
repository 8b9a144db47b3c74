#include "voxel/direction_set.h"

#include <cmath>
#include <numeric>
#include <stdexcept>

namespace rad {

namespace {

// Solid angle of [0,x] x [0,y] at distance d, seen from the origin: the corner term of the
// rectangle formula, atan(x y / (d sqrt(x^2 + y^2 + d^2))), signed by x and y.
double cornerSolidAngle(double x, double y, double d) {
  return std::atan2(x * y, d * std::sqrt(x * x + y * y + d * d));
}

bool insideBall(const IVec3& v, int radius) {
  return v.x * v.x + v.y * v.y + v.z * v.z <= radius * radius;
}

}  // namespace

double rectangleSolidAngle(double u0, double u1, double v0, double v1, double depth) {
  return cornerSolidAngle(u1, v1, depth) - cornerSolidAngle(u0, v1, depth) -
         cornerSolidAngle(u1, v0, depth) + cornerSolidAngle(u0, v0, depth);
}

DirectionSet::DirectionSet(int radius) : radius_(radius) {
  if (radius < 1) throw std::invalid_argument("DirectionSet: radius must be >= 1");
  for (int x = -radius; x <= radius; ++x)
    for (int y = -radius; y <= radius; ++y)
      for (int z = -radius; z <= radius; ++z) {
        const IVec3 v(x, y, z);
        if (!insideBall(v, radius)) continue;
        double solidAngle = 0.0;
        for (int axis = 0; axis < 3; ++axis)
          for (int sign : {-1, 1}) {
            IVec3 n = v;
            n[axis] += sign;
            if (insideBall(n, radius)) continue;
            // The exterior face lies in the plane axis = v[axis] + sign/2; it faces away from
            // the centre (shown in the header), so its solid angle counts positively.
            const int u = (axis + 1) % 3, w = (axis + 2) % 3;
            solidAngle += rectangleSolidAngle(v[u] - 0.5, v[u] + 0.5, v[w] - 0.5, v[w] + 0.5,
                                              std::abs(v[axis] + 0.5 * sign));
          }
        if (solidAngle == 0.0) continue;
        const int g = std::gcd(std::gcd(std::abs(x), std::abs(y)), std::abs(z));
        directions_.push_back({v / g, glm::normalize(Vec3d(v)), solidAngle});
      }
  // The enumeration is symmetric: direction i and size()-1-i are opposite.
  for (size_t i = 0; i < directions_.size() / 2; ++i) pairs_.push_back(uint32_t(i));
}

double DirectionSet::totalSolidAngle() const {
  double sum = 0.0;
  for (const DiscreteDirection& d : directions_) sum += d.solidAngle;
  return sum;
}

}  // namespace rad
