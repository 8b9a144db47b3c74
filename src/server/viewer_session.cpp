// The viewer's state: the lights the page asked for, the relighter that follows them, and the
// display mesh's colours.
#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/gltf_export.h>
#include <radiosity/ies_profile.h>
#include <radiosity/radiosity_method.h>
#include <radiosity/run_stats.h>
#include <radiosity/sensors.h>
#include <radiosity/surface_samples.h>
#include <radiosity/viewer_session.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <span>

#include "server/light_request.h"

namespace rad {

namespace {

using Json = nlohmann::json;

// The floats as the API sends them: their bytes (little-endian float32 on every supported machine).
std::string bytesOf(const std::vector<float>& values) {
  return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(float));
}

Json array(const Vec3& v) {
  return Json::array({v.x, v.y, v.z});
}

// A time the page may ask for (the ?t of /api/dynamic and /api/sensor).
void requireViewerTime(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0 || seconds > kMaxViewerSeconds)
    throw InputError("request ?t",
                     fmt::format("expected a time in [0, {:g}] s", kMaxViewerSeconds));
}

}  // namespace

ViewerSession::ViewerSession(std::unique_ptr<const RadiosityEngine> engine,
                             std::vector<Light> lights, std::unique_ptr<Relighting> relighting,
                             float displayEdge)
    : engine_(std::move(engine)),
      scene_(engine_->scene()),
      groups_(lightGroupsOf(scene_, lights)),
      state_{std::move(lights), std::vector<Color>(groups_.size(), Color(1.0f))},
      relighting_(std::move(relighting)) {
  start(displayEdge);
}

ViewerSession::ViewerSession(std::unique_ptr<const RadiosityEngine> engine,
                             std::vector<Light> lights, std::unique_ptr<SurfaceSolution> solution,
                             float displayEdge)
    : engine_(std::move(engine)),
      scene_(engine_->scene()),
      groups_(lightGroupsOf(scene_, lights)),
      state_{std::move(lights), std::vector<Color>(groups_.size(), Color(1.0f))},
      fixed_(std::move(solution)) {
  start(displayEdge);
}

void ViewerSession::start(float displayEdge) {
  display_ = cutSurfaces(scene_, displayEdge);
  glbOrder_ = glbVertexOrder(display_.mesh);
  shade();
  meshGlb_ = litMeshGlb(display_.mesh);
}

const SurfaceSolution& ViewerSession::solution() const {
  if (relighting_) return relighting_->solution();
  return *fixed_;
}

void ViewerSession::shade() {
  const SurfaceSolution& solution = this->solution();
  shadeSurfaces(display_, solution);
  colors_.resize(3 * glbOrder_.size());
  irradiance_.resize(3 * glbOrder_.size());
  tbb::parallel_for(size_t(0), glbOrder_.size(), [&](size_t k) {
    const uint32_t v = glbOrder_[k];
    std::memcpy(&colors_[3 * k], &display_.mesh.colors[v], 3 * sizeof(float));
    const Color h = solution.irradiance(display_.at[v]);
    std::memcpy(&irradiance_[3 * k], &h, 3 * sizeof(float));
  });
}

Json ViewerSession::summary() const {
  // The relight lock first, as applyLights takes them (the other order could deadlock).
  std::lock_guard relight(relightMutex_);
  std::lock_guard state(stateMutex_);
  Json lights = Json::array();
  for (size_t i = 0; i < state_.lights.size(); ++i) {
    const Light& l = state_.lights[i];
    Json light = {{"id", i},
                  {"type", lightTypeName(l.type)},
                  {"position", array(l.position)},
                  {"direction", array(l.direction)},
                  {"intensity", array(l.intensity)}};
    if (l.type == LightType::Spot) {
      light["inner_angle_deg"] = l.innerAngleDeg;
      light["outer_angle_deg"] = l.outerAngleDeg;
    }
    for (const LightGroup& g : groups_)
      for (uint32_t member : g.lights)
        if (member == i) light["group"] = g.name;
    lights.push_back(light);
  }
  Json groups = Json::array();
  for (size_t g = 0; g < groups_.size(); ++g)
    groups.push_back({{"name", groups_[g].name},
                      {"scale", array(state_.scales[g])},
                      {"lights", groups_[g].lights.size()},
                      {"emitting_materials", groups_[g].materials.size()}});
  const Camera camera = scene_.cameraOrDefault();
  const Bounds bounds = scene_.bounds();
  Json dynamicObjects = Json::array();
  for (const DynamicObject& o : scene_.dynamicObjects) dynamicObjects.push_back(o.name);
  Json sensorNames = Json::array();
  for (const SensorSet& set : scene_.sensors) sensorNames.push_back(set.name);
  const LengthUnit& unit = scene_.unit;
  return {{"scene", scene_.name},
          {"unit", unit.known() ? Json{{"name", unit.name}, {"metres", unit.metres}} : Json()},
          // The efficacy lux are taken at, the one IES and glTF candela are read with.
          {"lumens_per_watt", 1.0 / kWattsPerSrPerCandela},
          {"method", engine_->method().name()},
          {"patches", solution().elementCount()},
          {"relights", relighting_ != nullptr},
          {"vertices", glbOrder_.size()},
          {"lights", lights},
          {"groups", groups},
          {"camera",
           {{"eye", array(camera.eye)},
            {"target", array(camera.target)},
            {"up", array(camera.up)},
            {"fov_deg", camera.fovDeg}}},
          {"bounds", {{"min", array(bounds.min)}, {"max", array(bounds.max)}}},
          {"dynamic_objects", dynamicObjects},
          {"paths_end_s", pathsEnd()},
          {"sensor_sets", sensorNames},
          {"last_relight_ms", lastRelightMs_}};
}

double ViewerSession::pathsEnd() const {
  double end = 0.0;
  for (const DynamicObject& o : scene_.dynamicObjects)
    if (!o.path.empty()) end = std::max(end, o.path.back().t);
  return std::min(end, kMaxViewerSeconds);
}

Json ViewerSession::sensorAt(const SensorPoint& point, double seconds) const {
  requireViewerTime(seconds);
  const SensorPoint points[] = {point};
  std::vector<Color> irradiance;
  {
    std::lock_guard relight(relightMutex_);
    irradiance = engine_->sensorIrradiance(solution(), seconds, points, SensorSettings{});
  }
  const std::optional<double> lux = illuminanceLux(irradiance[0], scene_.unit);
  return {{"position", array(point.position)},
          {"normal", array(point.normal)},
          {"irradiance", array(irradiance[0])},
          {"illuminance_lux", lux ? Json(*lux) : Json()}};
}

Json ViewerSession::sensorSets(double seconds) const {
  requireViewerTime(seconds);
  const std::vector<SensorPoint> points = sensorPoints(scene_.sensors);
  std::vector<Color> irradiance;
  {
    std::lock_guard relight(relightMutex_);
    irradiance = engine_->sensorIrradiance(solution(), seconds, points, SensorSettings{});
  }
  Json sets = Json::object();
  for (const SensorReading& r : sensorReadings(scene_.sensors, irradiance, scene_.unit))
    sets[r.name] = toJson(r);
  return {{"t", seconds}, {"sets", sets}};
}

Json ViewerSession::objectsAt(double seconds) const {
  requireViewerTime(seconds);
  Json objects = Json::array();
  if (scene_.dynamicObjects.empty()) return {{"t", seconds}, {"objects", objects}};
  LitMesh mesh;
  {
    std::lock_guard relight(relightMutex_);
    engine_->objectsAt(solution(), seconds).appendObjects(mesh);
  }
  // appendObjects gives every triangle three vertices of its own, a group per object.
  for (const LitMeshGroup& g : mesh.groups) {
    std::vector<float> positions, colors;
    for (size_t v = 3 * size_t(g.firstTriangle); v < 3 * size_t(g.firstTriangle + g.triangleCount);
         ++v) {
      positions.insert(positions.end(),
                       {mesh.positions[v].x, mesh.positions[v].y, mesh.positions[v].z});
      colors.insert(colors.end(), {mesh.colors[v].r, mesh.colors[v].g, mesh.colors[v].b});
    }
    objects.push_back({{"name", g.name}, {"positions", positions}, {"colors", colors}});
  }
  return {{"t", seconds}, {"objects", objects}};
}

std::string ViewerSession::colors() const {
  std::lock_guard relight(relightMutex_);
  return bytesOf(colors_);
}

std::string ViewerSession::irradiance() const {
  std::lock_guard relight(relightMutex_);
  return bytesOf(irradiance_);
}

std::string ViewerSession::objectsCsv() const {
  std::lock_guard relight(relightMutex_);
  return objectRadiometryCsv(solution().objectRadiometry());
}

LightRequestRules ViewerSession::requestRules() const {
  LightRequestRules rules{scene_, groups_, "", ""};
  if (!fixed_) return rules;
  rules.noLights = fmt::format("a {} solution cannot be relit (serve --method {} moves lights)",
                               engine_->method().name(),
                               fmt::join(methodsWith(&MethodCapabilities::relight), "|"));
  if (fixed_->lightGroups().empty())
    rules.noGroups =
        fmt::format("this {} solution solved its light groups together", engine_->method().name());
  return rules;
}

std::string ViewerSession::applyLights(const Json& request, double* relightMs) {
  uint64_t mine = 0;
  {
    std::lock_guard state(stateMutex_);
    state_ = lightStateAfter(request, state_, requestRules());
    mine = ++asked_;
  }
  std::lock_guard relight(relightMutex_);
  if (reached_ < mine) {  // else a later request's relight already covered this one
    LightState asked;
    uint64_t newest = 0;
    {
      std::lock_guard state(stateMutex_);
      asked = state_;
      newest = asked_;
    }
    const std::vector<Light> lights = asked.effectiveLights(groups_);
    const std::vector<Color> emission = asked.emissionScales(scene_, groups_);
    const auto start = std::chrono::steady_clock::now();
    if (relighting_) {
      relighting_->relight(lights, emission);
    } else {
      fixed_->setGroupScales(asked.scales);  // the groups as solved, combined anew
    }
    shade();
    lastRelightMs_ =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    reached_ = newest;
  }
  if (relightMs) *relightMs = lastRelightMs_;
  return bytesOf(colors_);
}

}  // namespace rad
