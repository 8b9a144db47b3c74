#pragma once
// IES LM-63 (1995, 2002, 2019) photometric profiles: the luminous intensity distribution of a
// luminaire as a table of candela over vertical and horizontal angles.
// Layout and angle conventions: docs/references.md section 4 (AGi32's LM-63 pages, Ashdown's
// "Parsing the IESNA LM-63 photometric data file").

#include <string>
#include <vector>

namespace rad {

/// W/sr per candela for light given in photometric units (IES files without a "scale", glTF's
/// KHR_lights_punctual): 1/179, Radiance's luminous efficacy of uniform white light (179 lm/W).
constexpr double kWattsPerSrPerCandela = 1.0 / 179.0;
/// W per square metre per lux, at the same efficacy (glTF's directional lights, in lux).
constexpr double kWattsPerSquareMetrePerLux = kWattsPerSrPerCandela;

enum class PhotometricType { C = 1, B = 2, A = 3 };

struct IesProfile {
  std::string source;   // file name, for messages
  std::string version;  // "IESNA:LM-63-2002", ... or "LM-63-1986" when the file has no version line
  PhotometricType type = PhotometricType::C;
  double candelaMultiplier = 1.0;        // already applied to `candela`
  double ballastFactor = 1.0;            // already applied to `candela`
  std::vector<double> verticalAngles;    // degrees, ascending
  std::vector<double> horizontalAngles;  // degrees, ascending
  /// candela[h * verticalAngles.size() + v], multiplier and ballast factor applied.
  std::vector<double> candela;
  /// TILT=INCLUDE: lamp tilt angles (degrees) and multiplying factors; empty for TILT=NONE.
  std::vector<double> tiltAngles, tiltFactors;

  /// Candela toward a direction given in the luminaire frame (+z up, the light aimed down -z,
  /// +x along the 0-degree horizontal plane), bilinear in the table with the symmetry of the
  /// file unfolded; 0 outside the tabulated vertical range. `dir` need not be normalized.
  double candelaToward(double dx, double dy, double dz) const;
  /// Total luminous flux in lumens, the sin-weighted integral of the piecewise-linear table.
  double totalFlux() const;
  double maxCandela() const;
};

/// Parses LM-63 text. `source` names the file in error messages.
/// Throws InputError naming the source, the line and what was expected.
IesProfile parseIesProfile(const std::string& text, const std::string& source);
/// Reads and parses an .ies file. Throws InputError if it cannot be read or parsed.
IesProfile loadIesProfile(const std::string& path);

}  // namespace rad
