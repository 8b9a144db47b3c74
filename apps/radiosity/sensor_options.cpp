#include "sensor_options.h"

#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/message_text.h>

#include <CLI/CLI.hpp>
#include <set>

#include "command_support.h"

namespace rad::cli {

void SensorOptions::addTo(CLI::App& command) {
  command
      .add_option("--sensors", file_,
                  "Sensor points to measure, CSV: a row a point, x,y,z,nx,ny,nz[,name] (rows of "
                  "one name are a set); beside the scene's \"sensors\"")
      ->check(nonEmptyPath());
  command
      .add_option("--sensor-output", output_,
                  "Write what the sensors read as CSV: a row a point, its irradiance RGB (W per "
                  "square scene unit) and illuminance (lux, when the scene's unit is known)")
      ->check(nonEmptyPath());
  command
      .add_option("--sensor-rays", settings_.hemisphereRays,
                  "Rays a sensor gathers the surfaces' reflected light with (the path tracer: "
                  "paths a sensor)")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
}

void SensorOptions::prepare(const Scene& scene) {
  sets_ = scene.sensors;
  if (!file_.empty()) {
    std::set<std::string> names;
    for (const SensorSet& s : sets_) names.insert(s.name);
    for (SensorSet& s : readSensorCsv(file_)) {
      if (names.count(s.name))
        throw InputError(
            "--sensors " + file_,
            fmt::format("set {} is also one of the scene's sensors", quotedToken(s.name)));
      sets_.push_back(std::move(s));
    }
  }
  if (!output_.empty() && sets_.empty())
    throw InputError("--sensor-output",
                     "no sensors to measure: give --sensors FILE.csv or a scene with \"sensors\"");
  checkOutputPath("--sensor-output", output_);
}

void SensorOptions::measure(const Scene& scene, const Measure& irradiance, Console& console,
                            RunStats& stats) const {
  if (sets_.empty()) return;
  const std::vector<SensorPoint> points = sensorPoints(sets_);
  Stopwatch time;
  const std::vector<Color> measured = irradiance(points, settings_);
  stats.sensors = sensorReadings(sets_, measured, scene.unit);
  if (!scene.unit.known())
    console.warn(
        "sensors: the scene's length unit is not known (its \"unit\"), so they read irradiance "
        "in W per square scene unit and no lux");
  for (const SensorReading& r : stats.sensors) {
    if (r.lux.empty()) {
      console.info(fmt::format("sensors {}: {} point{}", r.name, r.points.size(),
                               r.points.size() == 1 ? "" : "s"));
      continue;
    }
    console.info(r.points.size() == 1
                     ? fmt::format("sensors {}: {:.4g} lx", r.name, r.meanLux)
                     : fmt::format("sensors {}: {} points, mean {:.4g} lx, min {:.4g}, max {:.4g}, "
                                   "uniformity {:.2f}",
                                   r.name, r.points.size(), r.meanLux, r.minLux, r.maxLux,
                                   r.uniformity));
  }
  if (!output_.empty()) writeSensorCsv(output_, stats.sensors, scene.unit);
  console.info(fmt::format("{} sensor point{} in {:.2f} s{}", points.size(),
                           points.size() == 1 ? "" : "s", time.seconds(),
                           output_.empty() ? "" : " -> " + output_));
}

}  // namespace rad::cli
