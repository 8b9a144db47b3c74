#pragma once
// Where the sun stands in the sky at a place and time, and how much light it sends on a clear
// day: what a scene's "sun" light is placed and sized by (scene_json.cpp).

#include <radiosity/types.h>

#include <string_view>

namespace rad {

/// A moment as an ISO 8601 date and time with its offset from UTC.
struct UtcTime {
  double julianDay = 0.0;  ///< days since noon UTC of 1 January 4713 BC (Julian calendar)
};

/// Reads "2026-06-21T12:00:00+02:00" (or "...Z"; seconds and their fraction optional). Returns
/// false, with `why` set, for anything else, including a time without its offset: the sun needs
/// the moment, not the wall clock.
bool parseIsoTime(std::string_view text, UtcTime& time, std::string& why);

/// The sun seen from a place on the Earth.
struct SunPosition {
  double elevationDeg = 0.0;  ///< above the horizon, with the atmosphere's refraction
  double azimuthDeg = 0.0;    ///< from north, clockwise seen from above (90: east)
};

/// The NOAA solar calculator's algorithm (after Meeus, "Astronomical Algorithms"; see
/// docs/references.md): accurate to about 0.01 degree for years 1800-2100. Latitude north and
/// longitude east in degrees.
SunPosition sunPosition(const UtcTime& time, double latitudeDeg, double longitudeDeg);

/// Direct normal illuminance of the sun under a clear sky, in lux: the IESNA Lighting Handbook's
/// E_dn = 127,500 lx x exp(-0.21 m), m = 1 / sin(elevation) the relative air mass; 0 below the
/// horizon.
double clearSkySunIlluminanceLux(double elevationDeg);

/// The unit vector toward the sun, in a scene whose `up` and `north` axes are given (unit,
/// perpendicular); east is north x up.
Vec3 towardSun(const SunPosition& sun, const Vec3& up, const Vec3& north);

}  // namespace rad
