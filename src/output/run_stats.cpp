#include <radiosity/atomic_file.h>
#include <radiosity/run_stats.h>

#include <glm/gtc/constants.hpp>
#include <nlohmann/json.hpp>

namespace rad {

namespace {

nlohmann::json rgb(const Color& c) {
  return nlohmann::json::array({c.r, c.g, c.b});
}

}  // namespace

nlohmann::json toJson(const SensorReading& r) {
  const bool lux = !r.lux.empty();
  nlohmann::json points = nlohmann::json::array();
  for (size_t i = 0; i < r.points.size(); ++i) {
    const SensorPoint& p = r.points[i];
    points.push_back({{"position", rgb(p.position)},
                      {"normal", rgb(p.normal)},
                      {"irradiance", rgb(r.irradiance[i])},
                      {"illuminance_lux", lux ? nlohmann::json(r.lux[i]) : nlohmann::json()}});
  }
  const auto luxOrNull = [&](double v) { return lux ? nlohmann::json(v) : nlohmann::json(); };
  return {{"points", points},
          {"mean_lux", luxOrNull(r.meanLux)},
          {"min_lux", luxOrNull(r.minLux)},
          {"max_lux", luxOrNull(r.maxLux)},
          {"uniformity", luxOrNull(r.uniformity)}};
}

Color absorbedPower(const Scene& scene, const std::vector<ObjectRadiometry>& objects,
                    std::span<const Color> emissionScales) {
  std::vector<Color> emitted(scene.objects.size(), Color(0.0f));
  for (const Face& f : scene.faces) {
    const Color scale = emissionScales.empty() ? Color(1.0f) : emissionScales[f.material];
    emitted[f.object] += scale * scene.materials[f.material].emission *
                         (glm::pi<float>() * float(scene.coveredArea(f)));
  }
  Color absorbed(0.0f);
  for (size_t i = 0; i < objects.size() && i < scene.objects.size(); ++i) {
    const ObjectRadiometry& o = objects[i];
    absorbed += o.meanIrradiance * float(o.area) - (o.meanRadiosity * float(o.area) - emitted[i]);
  }
  return absorbed;
}

nlohmann::json toJson(const RunStats& s) {
  nlohmann::json objects = nlohmann::json::array();
  for (const ObjectRadiometry& o : s.objects) {
    objects.push_back({{"name", o.name},
                       {"area", o.area},
                       {"mean_irradiance", rgb(o.meanIrradiance)},
                       {"mean_radiosity", rgb(o.meanRadiosity)}});
    if (o.groupShares.empty()) continue;
    nlohmann::json& shares = objects.back()["group_shares"] = nlohmann::json::object();
    for (size_t g = 0; g < o.groupShares.size() && g < s.lightGroups.size(); ++g)
      shares[s.lightGroups[g].name] = o.groupShares[g];
  }
  nlohmann::json j = {
      {"scene", s.scene},
      {"method", s.method},
      {"counts",
       {{"triangles", s.counts.triangles},
        {"patches", s.counts.patches},
        {"voxels", s.counts.voxels},
        {"directions", s.counts.directions},
        {"rays", s.counts.rays}}},
      {"timings_s",
       {{"load", s.timingsSeconds.load},
        {"prepare", s.timingsSeconds.prepare},
        {"solve", s.timingsSeconds.solve},
        {"render", s.timingsSeconds.render},
        {"total", s.timingsSeconds.total}}},
      {"iterations", s.iterations},
      {"residual", s.residual},
      {"residuals", s.residuals},
      {"energy", {{"emitted", rgb(s.emittedPower)}, {"absorbed", rgb(s.absorbedPower)}}},
      {"objects", objects},
      {"memory_peak_bytes", s.memoryPeakBytes},
      {"warnings", {{"count", s.warnings.size()}, {"messages", s.warnings}}},
  };
  if (s.converged) j["converged"] = *s.converged;
  if (!s.dynamicObjects.empty()) {
    nlohmann::json& objects = j["dynamic_objects"] = nlohmann::json::array();
    for (const RunStats::DynamicObjectEntry& d : s.dynamicObjects) {
      nlohmann::json lobes = nlohmann::json::object();
      const char* axes[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};
      for (size_t k = 0; k < 6; ++k) lobes[axes[k]] = rgb(d.lobes[k]);
      objects.push_back(
          {{"name", d.name}, {"mean_irradiance", rgb(d.meanIrradiance)}, {"lobes", lobes}});
    }
  }
  if (!s.lightGroups.empty()) {
    nlohmann::json& groups = j["light_groups"] = nlohmann::json::array();
    for (const RunStats::LightGroupEntry& g : s.lightGroups)
      groups.push_back({{"name", g.name}, {"scale", rgb(g.scale)}, {"power", rgb(g.power)}});
  }
  if (!s.sensors.empty()) {
    nlohmann::json& sensors = j["sensors"] = nlohmann::json::object();
    for (const SensorReading& r : s.sensors) sensors[r.name] = toJson(r);
  }
  if (!s.methodDetails.empty()) j[s.method] = s.methodDetails;
  if (!s.distributed.empty()) j["distributed"] = s.distributed;
  if (!s.settings.empty()) {
    nlohmann::json settings = nlohmann::json::object();
    for (const auto& setting : s.settings)
      std::visit([&](const auto& v) { settings[setting.first] = v; }, setting.second);
    j["settings"] = settings;
  }
  return j;
}

void writeRunStats(const std::string& path, const RunStats& stats) {
  // Names and warnings quote the input files, whose bytes need not be UTF-8.
  writeTextAtomically(
      path, toJson(stats).dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

}  // namespace rad
