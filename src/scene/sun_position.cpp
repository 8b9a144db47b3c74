// The NOAA solar calculator's equations (NOAA Global Monitoring Laboratory, "General Solar Position
// Calculations" and its spreadsheet, from Meeus, "Astronomical Algorithms", 1991):
// docs/references.md.
#include "scene/sun_position.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <string>

namespace rad {

namespace {

double radians(double deg) {
  return deg * std::numbers::pi / 180.0;
}
double degrees(double rad) {
  return rad * 180.0 / std::numbers::pi;
}

// The Julian day of a Gregorian calendar date at 0h UTC (Meeus, chapter 7).
double julianDayOf(int year, int month, int day) {
  if (month <= 2) year -= 1, month += 12;
  const int a = year / 100, b = 2 - a + a / 4;
  return std::floor(365.25 * (year + 4716)) + std::floor(30.6001 * (month + 1)) + day + b - 1524.5;
}

// Reads `digits` decimal digits at text[at], or -1.
int digitsAt(std::string_view text, size_t at, size_t digits) {
  if (at + digits > text.size()) return -1;
  int value = 0;
  const auto [end, error] = std::from_chars(text.data() + at, text.data() + at + digits, value);
  return error == std::errc() && end == text.data() + at + digits ? value : -1;
}

// Atmospheric refraction in degrees at a geometric elevation (the NOAA spreadsheet's fit).
double refractionDeg(double elevationDeg) {
  if (elevationDeg > 85.0) return 0.0;
  const double t = std::tan(radians(elevationDeg));
  double arcSeconds = 0.0;
  if (elevationDeg > 5.0)
    arcSeconds = 58.1 / t - 0.07 / (t * t * t) + 0.000086 / std::pow(t, 5.0);
  else if (elevationDeg > -0.575)
    arcSeconds =
        1735.0 +
        elevationDeg *
            (-518.2 + elevationDeg * (103.4 + elevationDeg * (-12.79 + elevationDeg * 0.711)));
  else
    arcSeconds = -20.772 / t;
  return arcSeconds / 3600.0;
}

}  // namespace

bool parseIsoTime(std::string_view text, UtcTime& time, std::string& why) {
  why = "expected a date and time with its offset, like 2026-06-21T12:00:00+02:00";
  const int year = digitsAt(text, 0, 4), month = digitsAt(text, 5, 2), day = digitsAt(text, 8, 2);
  const int hour = digitsAt(text, 11, 2), minute = digitsAt(text, 14, 2);
  if (year < 0 || month < 1 || month > 12 || hour < 0 || hour > 23 || minute < 0 || minute > 59 ||
      text[4] != '-' || text[7] != '-' || (text[10] != 'T' && text[10] != ' ') || text[13] != ':')
    return false;
  const bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
  const int monthDays[] = {31, leap ? 29 : 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (day < 1 || day > monthDays[month - 1]) return false;
  size_t at = 16;
  double seconds = 0.0;
  if (at < text.size() && text[at] == ':') {
    const int whole = digitsAt(text, at + 1, 2);
    if (whole < 0 || whole > 60) return false;
    seconds = whole, at += 3;
    if (at < text.size() && text[at] == '.') {
      double scale = 0.1;
      for (++at; at < text.size() && std::isdigit(static_cast<unsigned char>(text[at])); ++at)
        seconds += scale * (text[at] - '0'), scale *= 0.1;
    }
  }
  double offsetMinutes = 0.0;
  if (at + 1 == text.size() && text[at] == 'Z') {
    offsetMinutes = 0.0;
  } else if (at + 6 == text.size() && (text[at] == '+' || text[at] == '-') && text[at + 3] == ':') {
    const int h = digitsAt(text, at + 1, 2), m = digitsAt(text, at + 4, 2);
    if (h < 0 || h > 14 || m < 0 || m > 59) return false;
    offsetMinutes = (text[at] == '-' ? -1.0 : 1.0) * (60.0 * h + m);
  } else {
    why = "expected the time's offset from UTC at its end (Z, or +hh:mm / -hh:mm)";
    return false;
  }
  const double minutes = 60.0 * hour + minute + seconds / 60.0 - offsetMinutes;
  time.julianDay = julianDayOf(year, month, day) + minutes / 1440.0;
  why.clear();
  return true;
}

SunPosition sunPosition(const UtcTime& time, double latitudeDeg, double longitudeDeg) {
  const double jc = (time.julianDay - 2451545.0) / 36525.0;  // Julian centuries from J2000.0
  const double meanLong = std::fmod(280.46646 + jc * (36000.76983 + jc * 0.0003032), 360.0);
  const double meanAnomaly = 357.52911 + jc * (35999.05029 - 0.0001537 * jc);
  const double eccentricity = 0.016708634 - jc * (0.000042037 + 0.0000001267 * jc);
  const double m = radians(meanAnomaly);
  const double centre = std::sin(m) * (1.914602 - jc * (0.004817 + 0.000014 * jc)) +
                        std::sin(2.0 * m) * (0.019993 - 0.000101 * jc) +
                        std::sin(3.0 * m) * 0.000289;
  const double omega = radians(125.04 - 1934.136 * jc);
  const double apparentLong = meanLong + centre - 0.00569 - 0.00478 * std::sin(omega);
  const double meanObliquity =
      23.0 + (26.0 + (21.448 - jc * (46.815 + jc * (0.00059 - jc * 0.001813))) / 60.0) / 60.0;
  const double obliquity = radians(meanObliquity + 0.00256 * std::cos(omega));
  const double declination = std::asin(std::sin(obliquity) * std::sin(radians(apparentLong)));
  const double y = std::pow(std::tan(obliquity / 2.0), 2.0);
  const double l0 = radians(meanLong);
  const double equationOfTimeMin =
      4.0 * degrees(y * std::sin(2.0 * l0) - 2.0 * eccentricity * std::sin(m) +
                    4.0 * eccentricity * y * std::sin(m) * std::cos(2.0 * l0) -
                    0.5 * y * y * std::sin(4.0 * l0) -
                    1.25 * eccentricity * eccentricity * std::sin(2.0 * m));
  const double utcMinutes = std::fmod(time.julianDay + 0.5, 1.0) * 1440.0;
  const double trueSolarMin = std::fmod(
      std::fmod(utcMinutes + equationOfTimeMin + 4.0 * longitudeDeg, 1440.0) + 1440.0, 1440.0);
  const double hourAngle = radians(trueSolarMin / 4.0 - 180.0);
  const double lat = radians(latitudeDeg);
  const double cosZenith =
      std::clamp(std::sin(lat) * std::sin(declination) +
                     std::cos(lat) * std::cos(declination) * std::cos(hourAngle),
                 -1.0, 1.0);
  const double zenith = std::acos(cosZenith);
  // Azimuth from north, clockwise: atan2 of the east and north components of the sun's direction.
  const double east = -std::cos(declination) * std::sin(hourAngle);
  const double north = std::sin(declination) * std::cos(lat) -
                       std::cos(declination) * std::sin(lat) * std::cos(hourAngle);
  SunPosition sun;
  const double geometric = 90.0 - degrees(zenith);
  sun.elevationDeg = geometric + refractionDeg(geometric);
  sun.azimuthDeg = std::fmod(degrees(std::atan2(east, north)) + 360.0, 360.0);
  return sun;
}

double clearSkySunIlluminanceLux(double elevationDeg) {
  if (!(elevationDeg > 0.0)) return 0.0;
  const double airMass = 1.0 / std::sin(radians(elevationDeg));
  return 127500.0 * std::exp(-0.21 * airMass);
}

Vec3 towardSun(const SunPosition& sun, const Vec3& up, const Vec3& north) {
  const Vec3 east = glm::cross(north, up);
  const double el = radians(sun.elevationDeg), az = radians(sun.azimuthDeg);
  const Vec3 horizontal = float(std::cos(az)) * north + float(std::sin(az)) * east;
  return glm::normalize(float(std::cos(el)) * horizontal + float(std::sin(el)) * up);
}

}  // namespace rad
