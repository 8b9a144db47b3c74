// The sky models: the CIE standard overcast sky (Moon and Spencer 1942, adopted by the CIE in
// 1955) and the CIE clear sky (Kittler 1967, CIE 1973; ISO 15469:2004/CIE S 011 type 12), as
// docs/references.md 5.3 and 5.4 give them, and an equirectangular environment map (the
// latitude-longitude map of Debevec's light probes).
#include <radiosity/sky.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

namespace rad {

const char* skyModelName(SkyModel model) {
  switch (model) {
    case SkyModel::Uniform:
      return "uniform";
    case SkyModel::CieOvercast:
      return "cie-overcast";
    case SkyModel::CieClear:
      return "cie-clear";
    case SkyModel::Environment:
      break;
  }
  return "environment";
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

// The texel of an equirectangular map (its middle column along `forward`, rows by polar angle
// from `up`) the direction w falls in.
Color mapTexel(const Image& map, const Vec3& w, const Vec3& up, const Vec3& forward) {
  const Vec3 right = glm::cross(forward, up);
  const double azimuth = std::atan2(double(glm::dot(w, right)), double(glm::dot(w, forward)));
  const double polar = std::acos(std::clamp(double(glm::dot(w, up)), -1.0, 1.0));
  const double u = 0.5 + azimuth / (2.0 * glm::pi<double>()), v = polar / glm::pi<double>();
  const int x = std::clamp(int(u * map.width), 0, map.width - 1);
  const int y = std::clamp(int(v * map.height), 0, map.height - 1);
  return map.at(x, y);
}

}  // namespace

Color Sky::relativeRadiance(const Vec3& w) const {
  const float sinElevation = glm::dot(w, up);
  if (!(sinElevation > 0.0f)) return Color(0.0f);
  switch (model) {
    case SkyModel::Uniform:
      return Color(1.0f);
    case SkyModel::CieOvercast:
      return Color((1.0f + 2.0f * sinElevation) / 3.0f);
    case SkyModel::CieClear: {
      // Over its value at the zenith, where chi is the sun's zenith angle.
      const double sunCosZenith = glm::dot(towardSun, up);
      const double zenith = clearSkyShape(sunCosZenith, 1.0);
      return Color(float(clearSkyShape(glm::dot(w, towardSun), sinElevation) / zenith));
    }
    case SkyModel::Environment:
      return map ? mapTexel(*map, w, up, forward) : Color(0.0f);
  }
  return Color(0.0f);
}

}  // namespace rad
