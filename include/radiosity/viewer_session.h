#pragma once
// What the browser viewer shows and changes (radiosity serve): a solution kept up to date by its
// method's relighting as the page moves, aims, dims and switches lights (or, by a method that does
// not relight, shown and its light groups dimmed), and the display mesh it is drawn on (the
// scene's triangles cut to a viewing size, the same vertices whatever the solution's elements
// become) with each vertex's radiance. Thread-safe: the HTTP server calls it from many threads.
// A light group's scale dims its lights and its glowing surfaces alike. Relight requests that
// arrive while one runs are coalesced: the newest state wins, and every waiting request is
// answered with the colours of that state.

#include <radiosity/baked_mesh.h>
#include <radiosity/light_groups.h>
#include <radiosity/radiosity_engine.h>
#include <radiosity/relighting.h>
#include <radiosity/sensors.h>
#include <radiosity/surface_solution.h>

#include <cstdint>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace rad {

struct LightRequestRules;  // server/light_request.h

/// The latest time the viewer places dynamic objects at (a day).
inline constexpr double kMaxViewerSeconds = 86400.0;

class ViewerSession {
 public:
  /// Takes the engine (whose scene must outlive the session) and its relighting, solved for
  /// `lights`; the display mesh's edges are at most `displayEdge` (scene units).
  ViewerSession(std::unique_ptr<const RadiosityEngine> engine, std::vector<Light> lights,
                std::unique_ptr<Relighting> relighting, float displayEdge);
  /// A solution for `lights` by a method that does not relight: a light edit is refused, but
  /// its light groups, when it solved them apart, are dimmed and switched as asked.
  ViewerSession(std::unique_ptr<const RadiosityEngine> engine, std::vector<Light> lights,
                std::unique_ptr<SurfaceSolution> solution, float displayEdge);

  /// The scene, its lights (with ids, groups, and the state now) and the light groups, the
  /// camera and the mesh's size, as the page and scripts read them.
  nlohmann::json summary() const;
  /// The display mesh as binary glTF (colours clamped to [0, 1], as an export).
  const std::string& meshGlb() const { return meshGlb_; }
  /// Per display vertex in the .glb's vertex order: the linear radiance (3 little-endian float32).
  std::string colors() const;

  /// Per display vertex in the .glb's vertex order: the irradiance H (W per square scene unit,
  /// 3 little-endian float32), for the page's false-colour view.
  std::string irradiance() const;
  /// Each scene object's mean irradiance and radiosity now, as CSV (objectRadiometryCsv).
  std::string objectsCsv() const;

  /// The dynamic objects placed at `seconds` into their paths, lit by probes of the solution
  /// now (DynamicObjectLighting): {"t": seconds, "objects": [{"name", "positions": [x, y, z,
  /// ...], "colors": [r, g, b, ...]}]}, three vertices a triangle (CCW about its front), the
  /// colours the linear radiance leaving each. Throws InputError for a time that is negative,
  /// not finite or past kMaxViewerSeconds.
  nlohmann::json objectsAt(double seconds) const;
  /// What a sensor at `point` reads of the solution now, the dynamic objects placed at
  /// `seconds` (RadiosityEngine::sensorIrradiance): {"position", "normal", "irradiance" (W per
  /// square scene unit), "illuminance_lux" (null when the scene's unit is unknown)}. Throws
  /// InputError for a time as objectsAt does.
  nlohmann::json sensorAt(const SensorPoint& point, double seconds) const;
  /// What the scene's sensor sets read of the solution now, the objects placed at `seconds`:
  /// {"t", "sets": {name: the stats' form of the set (run_stats.h)}}. Throws InputError for a
  /// time as objectsAt does.
  nlohmann::json sensorSets(double seconds) const;
  /// The latest time the objects' paths set anything (0: none moves).
  double pathsEnd() const;

  /// Applies a light state: {"lights": [{"id": i, "position": [x, y, z], "direction": [...],
  /// "intensity": [...]}], "groups": {"name": scale or [r, g, b]}}, every field optional but
  /// the id. Checks all of it first and throws InputError (naming the field) without changing
  /// anything; then relights (coalesced) and returns the colours of the state it reached.
  std::string applyLights(const nlohmann::json& request, double* relightMs = nullptr);

 private:
  LightRequestRules requestRules() const;  // what a request may change here
  void shade();                            // under relightMutex_

  std::unique_ptr<const RadiosityEngine> engine_;
  const Scene& scene_;
  std::vector<LightGroup> groups_;
  SurfaceBake display_;
  std::vector<uint32_t> glbOrder_;
  std::string meshGlb_;

  mutable std::mutex stateMutex_;  ///< the asked state: state_, asked_
  LightState state_;
  uint64_t asked_ = 0;  ///< generation of the newest asked state

  mutable std::mutex relightMutex_;         ///< the relighting and what it shows
  std::unique_ptr<Relighting> relighting_;  ///< one of the two is set
  std::unique_ptr<SurfaceSolution> fixed_;
  const SurfaceSolution& solution() const;
  void start(float displayEdge);
  uint64_t reached_ = 0;  ///< generation the relighter and the colours are at
  double lastRelightMs_ = 0.0;
  std::vector<float> colors_, irradiance_;  ///< in .glb order
};

}  // namespace rad
