#pragma once
// The sensors of `render` and `solve`: the scene's "sensors" and a --sensors CSV measured after
// the solve (sensors.h), a line a set printed, --sensor-output written and the stats' "sensors".

#include <radiosity/run_stats.h>
#include <radiosity/scene.h>
#include <radiosity/sensors.h>

#include <functional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "console.h"

namespace CLI {
class App;
}  // namespace CLI

namespace rad::cli {

class SensorOptions {
 public:
  /// Adds --sensors, --sensor-output and --sensor-rays.
  void addTo(CLI::App& command);
  /// Reads the --sensors file and refuses, before any work, a --sensor-output that cannot be
  /// written or that asks for sensors there are none of. Call once the scene is loaded.
  void prepare(const Scene& scene);
  /// (option, path) of the output, for checkDistinctOutputs.
  std::pair<std::string, std::string> output() const { return {"--sensor-output", output_}; }
  bool any() const { return !sets_.empty(); }

  /// Irradiance at the points, as one method computes it.
  using Measure =
      std::function<std::vector<Color>(std::span<const SensorPoint>, const SensorSettings&)>;
  /// Measures every set (when there are any), prints a line a set, writes --sensor-output and
  /// puts the readings into `stats`.
  void measure(const Scene& scene, const Measure& irradiance, Console& console,
               RunStats& stats) const;

 private:
  std::string file_, output_;
  SensorSettings settings_;
  std::vector<SensorSet> sets_;  ///< the scene's, then the file's
};

}  // namespace rad::cli
