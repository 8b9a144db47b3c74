// The scene file's "sensors" (sensor_json.h).
#include "scene/io/sensor_json.h"

#include <radiosity/message_text.h>

#include <glm/geometric.hpp>
#include <set>

namespace rad {

namespace {

// At most this many points in one grid (a million: a room at 1 cm spacing).
constexpr int64_t kMaxGridPoints = 1'000'000;

// A unit normal from the file at `ptr`, refused when it has no direction.
Vec3 unitNormal(const JsonReader& r, const Json& j, const std::string& ptr) {
  const Vec3 n = r.vec3(j, ptr);
  const float length = glm::length(n);
  if (!(length > 0.0f) || !std::isfinite(length)) r.fail(ptr, "expected a non-zero vector");
  return n / length;
}

std::vector<SensorPoint> gridPoints(const JsonReader& r, const Json& entry,
                                    const std::string& ptr) {
  const std::string at = ptr + "/grid";
  const Json& g = entry["grid"];
  r.checkKeys(g, at, {"origin", "u", "v", "nu", "nv"});
  for (const char* key : {"origin", "u", "v", "nu", "nv"})
    if (!g.contains(key)) r.fail(at, fmt::format("missing key \"{}\"", key));
  const Vec3 origin = r.point(g["origin"], at + "/origin");
  const Vec3 u = r.point(g["u"], at + "/u"), v = r.point(g["v"], at + "/v");
  const int64_t nu = r.integer(g["nu"], at + "/nu", 1, kMaxGridPoints);
  const int64_t nv = r.integer(g["nv"], at + "/nv", 1, kMaxGridPoints);
  if (nu * nv > kMaxGridPoints)
    r.fail(at, fmt::format("{} x {} points: at most {} a grid", nu, nv, kMaxGridPoints));
  const Vec3 across = glm::cross(u, v);
  if (!(glm::length(across) > 0.0f)) r.fail(at, "u and v must span a plane (not parallel)");
  const Vec3 normal = entry.contains("normal") ? unitNormal(r, entry["normal"], ptr + "/normal")
                                               : glm::normalize(across);
  std::vector<SensorPoint> points;
  for (int64_t j = 0; j < nv; ++j)
    for (int64_t i = 0; i < nu; ++i)
      points.push_back(
          {origin + (float(i) + 0.5f) / float(nu) * u + (float(j) + 0.5f) / float(nv) * v, normal});
  return points;
}

SensorSet readSensor(const JsonReader& r, const Json& entry, const std::string& ptr, size_t index) {
  r.checkKeys(entry, ptr, {"name", "position", "normal", "grid"});
  SensorSet set;
  set.name = entry.contains("name") ? r.string(entry["name"], ptr + "/name")
                                    : fmt::format("sensor{}", index);
  if (set.name.empty()) r.fail(ptr + "/name", "expected a non-empty name");
  if (entry.contains("grid") == entry.contains("position"))
    r.fail(ptr, "expected either \"position\" (a point) or \"grid\" (a calculation grid)");
  if (entry.contains("grid")) {
    set.points = gridPoints(r, entry, ptr);
    return set;
  }
  if (!entry.contains("normal")) r.fail(ptr, "missing key \"normal\" (the way the sensor faces)");
  set.points.push_back({r.point(entry["position"], ptr + "/position"),
                        unitNormal(r, entry["normal"], ptr + "/normal")});
  return set;
}

}  // namespace

std::vector<SensorSet> readSensors(const JsonReader& r, const Json& list) {
  if (!list.is_array())
    r.fail("/sensors", fmt::format("expected an array, got {}", list.type_name()));
  std::vector<SensorSet> sets;
  std::set<std::string> names;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string ptr = fmt::format("/sensors/{}", i);
    sets.push_back(readSensor(r, list[i], ptr, i));
    if (!names.insert(sets.back().name).second)
      r.fail(ptr + "/name",
             fmt::format("{} names another sensor too", quotedToken(sets.back().name)));
  }
  return sets;
}

}  // namespace rad
