#pragma once
// Per-object results that every method reports (the `objects` table of the stats file).

#include <radiosity/types.h>

#include <string>
#include <vector>

namespace rad {

/// Area-weighted means over one scene object's front faces.
struct ObjectRadiometry {
  std::string name;
  double area = 0.0;
  Color meanIrradiance{0.0f};  ///< H, power per area arriving
  Color meanRadiosity{0.0f};   ///< B = E + rho H, power per area leaving
  /// Per light group (a solution's lightGroups()), its share of the object's radiosity
  /// (luminance, area-weighted; they sum to 1). Empty without groups.
  std::vector<double> groupShares;
};

}  // namespace rad
