#include "voxel/direction_set.h"

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>
#include <numeric>
#include <set>
#include <tuple>

namespace rad {
namespace {

TEST(DirectionSet, RadiusThirtyEightHas14790Directions) {
  // 14,790: the count Chatelier and Malgouyres give for R = 38; recounted independently with a
  // brute-force python3 loop over x^2 + y^2 + z^2 <= R^2 with a face-neighbour outside.
  const DirectionSet set(38);
  EXPECT_EQ(set.size(), 14790u);
  EXPECT_EQ(set.pairCount(), 14790u / 2);
}

TEST(DirectionSet, FactorsSumToFourPi) {
  for (int r : {1, 2, 5, 38}) {
    const DirectionSet set(r);
    EXPECT_NEAR(set.totalSolidAngle(), 4.0 * glm::pi<double>(), 1e-9) << "R = " << r;
  }
}

TEST(DirectionSet, PairsAreOppositeAndStepsPrimitive) {
  const DirectionSet set(12);
  for (size_t i = 0; i < set.size(); ++i) {
    const IVec3 s = set[i].step;
    EXPECT_EQ(std::gcd(std::gcd(std::abs(s.x), std::abs(s.y)), std::abs(s.z)), 1);
    const DiscreteDirection& opposite = set[set.size() - 1 - i];
    EXPECT_EQ(opposite.step, -s);
    EXPECT_NEAR(opposite.solidAngle, set[i].solidAngle, 1e-12);
  }
}

TEST(DirectionSet, RectangleSolidAngleMatchesClosedForms) {
  // A square of side 2 at distance 1, centred: one sixth of the sphere (a cube face), 4 pi / 6.
  EXPECT_NEAR(rectangleSolidAngle(-1, 1, -1, 1, 1), 4.0 * glm::pi<double>() / 6.0, 1e-12);
  // Far away the solid angle tends to area / d^2.
  EXPECT_NEAR(rectangleSolidAngle(-0.5, 0.5, -0.5, 0.5, 1000.0), 1e-6, 1e-12);
}

TEST(DirectionSet, FactorsAreAboutOneThousandthOfASteradianAtR38) {
  // The estimate: a direction covers about 1e-3 sr at R = 38 (4 pi / 14790 = 8.5e-4).
  const DirectionSet set(38);
  double smallest = 1.0, largest = 0.0;
  for (size_t i = 0; i < set.size(); ++i) {
    smallest = std::min(smallest, set[i].solidAngle);
    largest = std::max(largest, set[i].solidAngle);
  }
  EXPECT_GT(smallest, 1e-4);
  EXPECT_LT(largest, 3e-3);
}

}  // namespace
}  // namespace rad
