#pragma once
// The sky: light from every direction above the horizon, from beyond the scene. Its shape is a
// model of the sky's radiance relative to a reference (the zenith's, or the uniform sky's); a
// sky light (LightType::Sky) holds the reference radiance as its intensity, so that light groups
// and relights scale it as any light. Below the horizon it is black: a ground is geometry.

#include <radiosity/image.h>
#include <radiosity/types.h>

#include <cstdint>
#include <memory>

namespace rad {

/// Uniform: the same radiance everywhere above the horizon. CieOvercast: the CIE standard
/// overcast sky, L(gamma) = Lz (1 + 2 sin gamma) / 3 (docs/references.md 5.3). CieClear: the CIE
/// clear sky about the sun (5.4). Environment: an equirectangular map of radiance.
enum class SkyModel : uint8_t { Uniform, CieOvercast, CieClear, Environment };
/// "uniform", "cie-overcast", "cie-clear" or "environment", as the scene file spells it.
const char* skyModelName(SkyModel model);

struct Sky {
  SkyModel model = SkyModel::Uniform;
  Vec3 up{0.0f, 1.0f, 0.0f};         ///< unit; the zenith
  Vec3 towardSun{0.0f, 1.0f, 0.0f};  ///< unit; CieClear only
  /// Environment: the map, row 0 at the zenith and the last at the nadir (rows by polar angle),
  /// columns by azimuth, its middle column looking along `forward` and the columns to its right
  /// along forward x up; the share of the map below the horizon is not used.
  std::shared_ptr<const Image> map;
  Vec3 forward{0.0f, 0.0f, -1.0f};  ///< unit, horizontal

  /// The radiance arriving from the unit direction `w` (pointing into the sky) over the
  /// reference radiance: 1 for a uniform sky, 1 at the zenith for the CIE skies, the map's texel
  /// for an environment; 0 at or below the horizon.
  Color relativeRadiance(const Vec3& w) const;
  bool operator==(const Sky&) const = default;
};

}  // namespace rad
