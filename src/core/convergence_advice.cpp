#include "core/convergence_advice.h"

#include <fmt/format.h>

#include <cmath>

namespace rad {

std::string remainingStepsAdvice(std::span<const double> residuals, double tolerance,
                                 const std::string& step) {
  const size_t n = residuals.size();
  if (n < 2 || !(residuals[n - 2] > 0.0) || !(tolerance > 0.0)) return "";
  const double rate = residuals[n - 1] / residuals[n - 2];
  if (!(rate > 0.0 && rate < 1.0)) return "";
  return fmt::format(" (at its last rate, {:.4f} a {}, about {:.0f} more)", rate, step,
                     std::ceil(std::log(tolerance / residuals[n - 1]) / std::log(rate)));
}

std::string nearWhiteAdvice(float rhoMax) {
  if (rhoMax < 0.95f) return "";
  return fmt::format(
      "; reflectances near 1 converge slowly: here up to {:.3f}, whose light bounces about "
      "1 / (1 - rho) = {:.0f} times (a texture lost on import leaves a material at its factor, "
      "often 1)",
      rhoMax, 1.0 / (1.0 - double(rhoMax)));
}

}  // namespace rad
