#pragma once
// The stats file of a run (`--stats FILE.json`); its fields are the contract in
// docs/ARCHITECTURE.md ("Stats JSON"): scripts and the tests read them.

#include <radiosity/object_radiometry.h>
#include <radiosity/scene.h>
#include <radiosity/sensors.h>
#include <radiosity/types.h>

#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace rad {

struct RunStats {
  std::string scene;
  std::string method;
  struct Counts {
    uint64_t triangles = 0, patches = 0, voxels = 0, directions = 0, rays = 0;
  } counts;
  struct Timings {
    double load = 0, prepare = 0, solve = 0, render = 0, total = 0;
  } timingsSeconds;
  int iterations = 0;
  double residual = 0.0;
  /// The radiosity methods': whether the residual fell below the tolerance (written as
  /// "converged"); unset for the path tracer, which does not iterate.
  std::optional<bool> converged;
  std::vector<double> residuals;  ///< per iteration, for methods that iterate
  Color emittedPower{0.0f};       ///< W, every emitter and light
  Color absorbedPower{0.0f};      ///< W, sum of (1 - rho) H A over the objects
  std::vector<ObjectRadiometry> objects;
  /// The light groups solved apart (objects' groupShares are in this order), with their scales
  /// and the power (W) each emits at its scale; empty: solved together.
  struct LightGroupEntry {
    std::string name;
    Color scale{1.0f}, power{0.0f};
  };
  std::vector<LightGroupEntry> lightGroups;
  std::vector<Color> emissionScales;  ///< per material, its group's scale (empty: none)
  /// Per dynamic object: its mean irradiance and its reflected light's six lobes (W/sr along
  /// +x, -x, +y, -y, +z, -z).
  struct DynamicObjectEntry {
    std::string name;
    Color meanIrradiance{0.0f};
    std::array<Color, 6> lobes{};
  };
  std::vector<DynamicObjectEntry> dynamicObjects;
  /// The sensor sets measured (sensors.h), under "sensors" by name.
  std::vector<SensorReading> sensors;
  uint64_t memoryPeakBytes = 0;
  /// Numbers particular to the method, written under the method's name ("voxel": {...}).
  nlohmann::json methodDetails;
  /// A run split among processes (MPI ranks): their count, each one's seconds, the bytes sent
  /// and received; empty for one process.
  nlohmann::json distributed;
  /// The settings the method ran with, by name (solver_settings.h), under "settings".
  std::vector<std::pair<std::string, SettingValue>> settings;
  /// The run's warnings, printed or not (--quiet), under "warnings": their count and messages.
  std::vector<std::string> warnings;
};

/// Power absorbed by the objects, sum of (1 - rho) H A = H A - (B - E) A with E the objects'
/// emitted radiosity (each material's emission times `emissionScales`, when given), from their
/// mean irradiance and radiosity.
Color absorbedPower(const Scene& scene, const std::vector<ObjectRadiometry>& objects,
                    std::span<const Color> emissionScales = {});

nlohmann::json toJson(const RunStats& stats);
/// A sensor set as the stats' "sensors" hold it: its points (position, normal, irradiance,
/// illuminance_lux), mean_lux, min_lux, max_lux and uniformity (lux null when the unit is
/// unknown).
nlohmann::json toJson(const SensorReading& reading);
/// Writes the stats as indented JSON, atomically (temporary file + rename).
void writeRunStats(const std::string& path, const RunStats& stats);

}  // namespace rad
