#pragma once
// The reference path tracer: unbiased diffuse light transport that every other method is
// checked against. Next-event estimation on emissive triangles (chosen by power) and on point,
// spot and IES lights; cosine-weighted bounces; Russian roulette. Deterministic for a given seed
// whatever the thread count (each pixel tile and each sample point has its own random stream).

#include <radiosity/image.h>
#include <radiosity/object_radiometry.h>
#include <radiosity/process_share.h>
#include <radiosity/progress.h>
#include <radiosity/ray_caster.h>
#include <radiosity/scene.h>
#include <radiosity/sensors.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace rad {

struct PathTracerSettings {
  int samplesPerPixel = 64;
  int maxDepth = 256;  ///< bounce limit; Russian roulette ends paths long before it in practice
  uint64_t seed = 1;
  /// Where a render keeps its finished tiles (every half minute, and when stopped) and goes on
  /// from them when run again after a kill or Ctrl-C, to the same picture; empty: nowhere.
  /// Not in a split render.
  std::string checkpointDir;
  /// A render split among processes: each renders every count-th tile from its rank, and the
  /// tiles are added up (each pixel from one process: the same picture, bit for bit).
  ProcessShare processes;
  /// Each pixel the irradiance arriving where its camera ray meets a surface, on the side it
  /// sees (W per square scene unit; an irradiance path a sample), not the radiance leaving it:
  /// a false-colour picture's (false_colour.h).
  bool irradiance = false;
};

struct PathTracerStats {
  uint64_t rays = 0;   ///< closest-hit and shadow rays cast
  uint64_t paths = 0;  ///< camera paths or irradiance samples traced
  double seconds = 0.0;
  size_t resumedTiles = 0;            ///< tiles a checkpoint brought (16 x 16 pixels each)
  std::vector<std::string> warnings;  ///< a checkpoint not read or not written, and why
};

struct PathTracedImage {
  Image image;  ///< linear radiance
  PathTracerStats stats;
};

/// Renders the scene as seen by `camera` (camera.width x camera.height pixels).
/// Throws rad::Cancelled if `progress` returns false.
PathTracedImage renderPathTraced(const Scene& scene, const Camera& camera,
                                 const PathTracerSettings& settings,
                                 const ProgressCallback& progress = {});
/// The same through `caster` (built over `scene`), shared with the run's other stages.
PathTracedImage renderPathTraced(const Scene& scene, const RayCaster& caster, const Camera& camera,
                                 const PathTracerSettings& settings,
                                 const ProgressCallback& progress = {});

/// Area-weighted mean irradiance and radiosity of every scene object, estimated at
/// `pointsPerObject` stratified points on its faces with `settings.samplesPerPixel` irradiance
/// paths each. The ground truth for the per-surface comparisons of the radiosity methods.
std::vector<ObjectRadiometry> estimateObjectRadiometry(const Scene& scene, int pointsPerObject,
                                                       const PathTracerSettings& settings,
                                                       PathTracerStats* stats = nullptr,
                                                       const ProgressCallback& progress = {});
/// The same through `caster` (built over `scene`), shared with the run's other stages.
std::vector<ObjectRadiometry> estimateObjectRadiometry(const Scene& scene, const RayCaster& caster,
                                                       int pointsPerObject,
                                                       const PathTracerSettings& settings,
                                                       PathTracerStats* stats = nullptr,
                                                       const ProgressCallback& progress = {});

/// Irradiance (W per square scene unit) at each sensor point, the mean of
/// `sensors.hemisphereRays` irradiance paths (next-event estimation, then bounces) through
/// `caster` (built over `scene`): the reference for sensorIrradiance (sensors.h).
std::vector<Color> estimateSensorIrradiance(const Scene& scene, const RayCaster& caster,
                                            std::span<const SensorPoint> points,
                                            const SensorSettings& sensors,
                                            const PathTracerSettings& settings,
                                            PathTracerStats* stats = nullptr,
                                            const ProgressCallback& progress = {});

}  // namespace rad
