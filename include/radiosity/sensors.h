#pragma once
// Sensors: the light at the points a lighting designer asks about (a desk, a work plane's
// calculation grid), as a lux meter there would read it. Irradiance at a sensor is what arrives
// at that point and orientation, not the mean of the patch or voxel side it lies on: the direct
// light of lights and emitting surfaces by shadow rays (DirectLighting, the physics every method
// shares), and the light the surfaces reflect gathered from the solution over the hemisphere.
// The path tracer estimates the same integral by itself (RadiosityMethod::estimateSensors).
// Units: irradiance in W per square scene unit; illuminance in lux, 179 lm/W on the luminance
// Y = 0.2126 R + 0.7152 G + 0.0722 B (docs/references.md 5).

#include <radiosity/progress.h>
#include <radiosity/ray_caster.h>
#include <radiosity/scene.h>
#include <radiosity/surface_radiance.h>

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace rad {

struct SensorSettings {
  /// Rays a point gathers the surfaces' reflected light with (cosine-weighted, one in each cell
  /// of the smallest square grid of at least this many); the path tracer's paths a point. At
  /// 256, 10,000 points of a 130k-patch room differ from 1,024's by 0.3% (median), 1.6% (95th
  /// percentile); the path tracer's direct light from a small emitter needs thousands.
  int hemisphereRays = 256;
  /// Shadow rays toward each emitting triangle, whose unoccluded light is exact (its form
  /// factor) and whose visible share they estimate.
  int emitterSamples = 16;
  uint64_t seed = 1;
};

/// Throws InputError naming `source` for settings out of range.
void validateSensorSettings(const SensorSettings& settings, const std::string& source);

/// Irradiance (W per square scene unit) at each point, from the light `radiance` leaves the
/// surfaces of `scene` with (a solution, or the scene with its objects placed), its direct
/// lights and its emission scales; `caster` is built over `scene`. Safe for any number of points:
/// they are split among threads. Throws rad::Cancelled if `progress` returns false.
std::vector<Color> sensorIrradiance(const Scene& scene, const RayCaster& caster,
                                    const SurfaceRadiance& radiance,
                                    std::span<const SensorPoint> points,
                                    const SensorSettings& settings,
                                    const ProgressCallback& progress = {});

/// Illuminance in lux of an irradiance in W per `unit`^2; nullopt when the unit is unknown.
std::optional<double> illuminanceLux(const Color& irradiance, const LengthUnit& unit);

/// A sensor set's answer: per point its irradiance and, when the scene's unit is known, its
/// illuminance, with the figures a lighting designer checks against a standard (EN 12464-1
/// asks for a mean and a uniformity min / mean).
struct SensorReading {
  std::string name;
  std::vector<SensorPoint> points;
  std::vector<Color> irradiance;  ///< W per square scene unit
  std::vector<double> lux;        ///< per point; empty when the unit is unknown
  double meanLux = 0.0, minLux = 0.0, maxLux = 0.0;
  double uniformity = 0.0;  ///< min / mean; 0 when the mean is 0
};

/// The readings of `sets`, whose points' irradiance `irradiance` holds in the same order (all the
/// sets' points one after another).
std::vector<SensorReading> sensorReadings(std::span<const SensorSet> sets,
                                          std::span<const Color> irradiance,
                                          const LengthUnit& unit);
/// Every point of `sets`, in order.
std::vector<SensorPoint> sensorPoints(std::span<const SensorSet> sets);

/// Reads sensors from a CSV file: a row a point, `x,y,z,nx,ny,nz[,name]` (a first row that is
/// not numbers is a header; empty lines and lines starting with '#' are skipped). Rows of one
/// name form a set; rows without a name, a set named after the file (its stem). Normals are
/// normalised. Throws InputError naming the file and line for a bad row.
std::vector<SensorSet> readSensorCsv(const std::string& path);
/// Writes the readings as CSV, a row a point: set, index, position, normal, irradiance RGB (W
/// per square `unit`) and illuminance in lux (empty when the unit is unknown); atomically.
void writeSensorCsv(const std::string& path, std::span<const SensorReading> readings,
                    const LengthUnit& unit);

}  // namespace rad
