// What the sensors read, as a lighting designer reads it: lux per point, and per set the mean,
// the extremes and the uniformity; written as CSV.
#include <fmt/format.h>
#include <radiosity/atomic_file.h>
#include <radiosity/ies_profile.h>
#include <radiosity/sensors.h>

#include <algorithm>
#include <stdexcept>

#include "output/csv_field.h"

namespace rad {

std::optional<double> illuminanceLux(const Color& irradiance, const LengthUnit& unit) {
  if (!unit.known()) return std::nullopt;
  // W per unit^2 -> W/m^2 (a square metre holds 1 / metres^2 of them), then lm at 179 lm/W.
  return double(luminance(irradiance)) / (unit.metres * unit.metres) / kWattsPerSquareMetrePerLux;
}

std::vector<SensorPoint> sensorPoints(std::span<const SensorSet> sets) {
  std::vector<SensorPoint> points;
  for (const SensorSet& set : sets)
    points.insert(points.end(), set.points.begin(), set.points.end());
  return points;
}

std::vector<SensorReading> sensorReadings(std::span<const SensorSet> sets,
                                          std::span<const Color> irradiance,
                                          const LengthUnit& unit) {
  size_t count = 0;
  for (const SensorSet& set : sets) count += set.points.size();
  if (irradiance.size() != count)
    throw std::invalid_argument("sensorReadings: one irradiance a point");
  std::vector<SensorReading> readings;
  size_t next = 0;
  for (const SensorSet& set : sets) {
    SensorReading r{set.name, set.points, {}, {}};
    r.irradiance.assign(irradiance.begin() + ptrdiff_t(next),
                        irradiance.begin() + ptrdiff_t(next + set.points.size()));
    next += set.points.size();
    if (unit.known() && !r.irradiance.empty()) {
      for (const Color& e : r.irradiance) r.lux.push_back(*illuminanceLux(e, unit));
      r.minLux = *std::min_element(r.lux.begin(), r.lux.end());
      r.maxLux = *std::max_element(r.lux.begin(), r.lux.end());
      double sum = 0.0;
      for (double lux : r.lux) sum += lux;
      r.meanLux = sum / double(r.lux.size());
      r.uniformity = r.meanLux > 0.0 ? r.minLux / r.meanLux : 0.0;
    }
    readings.push_back(std::move(r));
  }
  return readings;
}

void writeSensorCsv(const std::string& path, std::span<const SensorReading> readings,
                    const LengthUnit& unit) {
  std::string text = "set,index,x,y,z,nx,ny,nz,H_r,H_g,H_b,lux\n";
  for (const SensorReading& r : readings)
    for (size_t i = 0; i < r.points.size(); ++i) {
      const SensorPoint& p = r.points[i];
      const Color& h = r.irradiance[i];
      text += fmt::format("{},{},{:g},{:g},{:g},{:g},{:g},{:g},{:g},{:g},{:g},{}\n",
                          csvField(r.name), i, p.position.x, p.position.y, p.position.z, p.normal.x,
                          p.normal.y, p.normal.z, h.r, h.g, h.b,
                          unit.known() ? fmt::format("{:g}", r.lux[i]) : std::string());
    }
  writeTextAtomically(path, text);
}

}  // namespace rad
