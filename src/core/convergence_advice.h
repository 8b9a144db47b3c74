#pragma once
// What a solve that ended above its tolerance tells the user to change, in the same words for every
// method: how many more steps its residual's last rate of fall asks for, and why reflectances near
// 1 are slow.

#include <span>
#include <string>

namespace rad {

/// " (at its last rate, R a STEP, about N more)": the steps that `residuals` (one a step, the last
/// above `tolerance`) would still take to reach `tolerance` if they kept falling at the ratio of
/// their last two; "" when they do not fall, or tolerance is 0.
std::string remainingStepsAdvice(std::span<const double> residuals, double tolerance,
                                 const std::string& step);
/// "; reflectances near 1 converge slowly: ..." when the largest reflectance `rhoMax` is 0.95 or
/// more (its light bounces about 1 / (1 - rho) times), else "".
std::string nearWhiteAdvice(float rhoMax);

}  // namespace rad
