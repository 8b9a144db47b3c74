// The sky models: the CIE standard overcast sky (Moon and Spencer 1942, adopted by the CIE in
// 1955) and the CIE clear sky (Kittler 1967, CIE 1973; ISO 15469:2004/CIE S 011 type 12), as
// docs/references.md 5.3 and 5.4 give them.
#include <radiosity/sky.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace rad {

const char* skyModelName(SkyModel model) {
  switch (model) {
    case SkyModel::Uniform:
      return "uniform";
    case SkyModel::CieOvercast:
      return "cie-overcast";
    case SkyModel::CieClear:
      break;
  }
  return "cie-clear";
}

namespace {

// The CIE clear sky's indicatrix (scattering by angle chi from the sun) times its gradation
// (brightening toward the horizon) at zenith angle `cosZenith`: L / Lz up to the sun's factor.
double clearSkyShape(double cosChi, double cosZenith) {
  const double chi = std::acos(std::clamp(cosChi, -1.0, 1.0));
  const double indicatrix = 0.91 + 10.0 * std::exp(-3.0 * chi) + 0.45 * cosChi * cosChi;
  const double gradation = 1.0 - std::exp(-0.32 / cosZenith);
  return indicatrix * gradation;
}

}  // namespace

float Sky::relativeRadiance(const Vec3& w) const {
  const float sinElevation = glm::dot(w, up);
  if (!(sinElevation > 0.0f)) return 0.0f;
  switch (model) {
    case SkyModel::Uniform:
      return 1.0f;
    case SkyModel::CieOvercast:
      return (1.0f + 2.0f * sinElevation) / 3.0f;
    case SkyModel::CieClear: {
      // Over its value at the zenith, where chi is the sun's zenith angle.
      const double sunCosZenith = glm::dot(towardSun, up);
      const double zenith = clearSkyShape(sunCosZenith, 1.0);
      return float(clearSkyShape(glm::dot(w, towardSun), sinElevation) / zenith);
    }
  }
  return 0.0f;
}

}  // namespace rad
