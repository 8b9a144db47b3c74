// POST /api/lights's body read and checked whole before anything changes.
#include "server/light_request.h"

#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/scene_builder.h>

#include <cmath>
#include <glm/gtx/component_wise.hpp>

namespace rad {

namespace {

using Json = nlohmann::json;

[[noreturn]] void refuse(const std::string& where, const std::string& what) {
  throw InputError("request " + where, what);
}

Vec3 vec3(const Json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 3) refuse(where, "expected an array of 3 numbers");
  Vec3 v;
  for (int k = 0; k < 3; ++k) {
    if (!j[size_t(k)].is_number()) refuse(where, "expected an array of 3 numbers");
    v[k] = j[size_t(k)].get<float>();
    if (!std::isfinite(v[k])) refuse(where, "expected finite numbers");
  }
  return v;
}

// A light's intensity or a group's scale: as a scene file may hold them, in [0, kMaxLight].
Color nonNegative(const Json& j, const std::string& where) {
  if (j.is_number() && !std::isfinite(j.get<double>())) refuse(where, "expected finite numbers");
  const Color c = j.is_number() ? Color(j.get<float>()) : vec3(j, where);
  if (!(minComponent(c) >= 0.0f) || !(maxComponent(c) <= kMaxLight))
    refuse(where, fmt::format("expected numbers in [0, {:g}]", kMaxLight));
  return c;
}

// Why the lights at these group scales would be more light than a scene may hold (an intensity
// or an emission times its group's scale beyond kMaxLight), or "".
std::string tooMuchLight(const Scene& scene, const LightState& state,
                         std::span<const LightGroup> groups) {
  for (size_t g = 0; g < groups.size(); ++g) {
    for (uint32_t i : groups[g].lights)
      if (!(maxComponent(state.lights[i].intensity * state.scales[g]) <= kMaxLight))
        return fmt::format("light {}'s intensity times group '{}''s scale is beyond {:g} W/sr", i,
                           groups[g].name, kMaxLight);
    for (uint32_t m : groups[g].materials)
      if (!(maxComponent(scene.materials[m].emission * state.scales[g]) <= kMaxLight))
        return fmt::format("material '{}''s emission times group '{}''s scale is beyond {:g}",
                           scene.materials[m].name, groups[g].name, kMaxLight);
  }
  return "";
}

// One entry of "lights" applied to `lights`.
void editLight(const Json& edit, size_t k, std::vector<Light>& lights) {
  const std::string at = fmt::format("/lights/{}", k);
  if (!edit.is_object() || !edit.contains("id") || !edit["id"].is_number_integer())
    refuse(at, "expected an object with an integer \"id\"");
  const int64_t id = edit["id"].get<int64_t>();
  if (id < 0 || size_t(id) >= lights.size())
    refuse(at + "/id", lights.empty()
                           ? "the scene has no light"
                           : fmt::format("no light {} (ids 0 to {})", id, lights.size() - 1));
  Light& light = lights[size_t(id)];
  for (const auto& [key, value] : edit.items()) {
    if (key == "id") continue;
    if (key == "position") {
      if (!light.positional())
        refuse(at + "/position",
               fmt::format("a {} light has no position", lightTypeName(light.type)));
      light.position = vec3(value, at + "/position");
      if (glm::compMax(glm::abs(light.position)) > kMaxSceneCoordinate)
        refuse(at + "/position", fmt::format("beyond {:g} scene units", kMaxSceneCoordinate));
    } else if (key == "direction") {
      if (light.type == LightType::Sky) refuse(at + "/direction", "a sky has no direction");
      const Vec3 d = vec3(value, at + "/direction");
      // Scaled to a largest component of 1 first: the length of [1e20, 0, 0] overflows.
      const float largest = glm::compMax(glm::abs(d));
      if (!(largest > 0.0f)) refuse(at + "/direction", "zero length");
      light.direction = glm::normalize(d / largest);
    } else if (key == "intensity") {
      light.intensity = nonNegative(value, at + "/intensity");
    } else {
      refuse(at + "/" + key, "unknown key (expected id, position, direction, intensity)");
    }
  }
}

}  // namespace

Json lightRequestJson(std::string_view body) {
  // A NUL byte ends the JSON text for the parser, and what follows would pass unread.
  if (body.find('\0') != std::string_view::npos) refuse("", "the body holds a NUL byte");
  Json json = Json::parse(body, nullptr, false);
  if (json.is_discarded()) refuse("", "the body is not valid JSON");
  return json;
}

LightState lightStateAfter(const Json& request, const LightState& now,
                           const LightRequestRules& rules) {
  if (!request.is_object()) refuse("", "expected a JSON object with \"lights\" and/or \"groups\"");
  for (const auto& [key, value] : request.items())
    if (key != "lights" && key != "groups")
      refuse("/" + key, "unknown key (expected \"lights\" or \"groups\")");
  if (request.contains("lights") && !rules.noLights.empty()) refuse("/lights", rules.noLights);
  if (request.contains("groups") && !rules.noGroups.empty()) refuse("/groups", rules.noGroups);
  LightState next = now;
  if (request.contains("lights")) {
    const Json& list = request["lights"];
    if (!list.is_array()) refuse("/lights", "expected an array");
    for (size_t k = 0; k < list.size(); ++k) editLight(list[k], k, next.lights);
  }
  if (request.contains("groups")) {
    const Json& map = request["groups"];
    if (!map.is_object()) refuse("/groups", "expected an object of group name: scale");
    for (const auto& [name, value] : map.items()) {
      size_t g = 0;
      while (g < rules.groups.size() && rules.groups[g].name != name) ++g;
      if (g == rules.groups.size()) refuse("/groups/" + name, "no such light group");
      next.scales[g] = nonNegative(value, "/groups/" + name);
    }
  }
  if (const std::string why = tooMuchLight(rules.scene, next, rules.groups); !why.empty())
    refuse(request.contains("groups") ? "/groups" : "/lights", why);
  return next;
}

}  // namespace rad
