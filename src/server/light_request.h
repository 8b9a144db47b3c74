#pragma once
// The body of POST /api/lights read into a light state, without a server or a session: the
// parsing the viewer's server does and the fuzz target lights_body_fuzzer drives.
//   {"lights": [{"id": i, "position": [x, y, z], "direction": [...], "intensity": [...]}],
//    "groups": {"name": scale or [r, g, b]}}, every field optional but each light's id.

#include <radiosity/light_groups.h>
#include <radiosity/scene.h>

#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rad {

/// What a session lets a request change.
struct LightRequestRules {
  const Scene& scene;
  std::span<const LightGroup> groups;
  std::string noLights;  ///< why "lights" is refused ("": lights may move and change)
  std::string noGroups;  ///< why "groups" is refused ("": groups may be scaled)
};

/// The JSON of a body as received. Throws InputError ("request", why) for a NUL byte (the parser
/// would stop there and what follows pass unread) or text that is not JSON.
nlohmann::json lightRequestJson(std::string_view body);

/// The state `request` asks for, from `now`. Checks all of it and throws InputError naming the
/// field ("request /lights/0/direction") for an unknown key, light or group, a wrong shape, a
/// value not finite or negative, a position beyond kMaxSceneCoordinate, a zero direction, or an
/// intensity or emission that times its group's scale is beyond kMaxLight. A direction comes
/// back of length 1.
LightState lightStateAfter(const nlohmann::json& request, const LightState& now,
                           const LightRequestRules& rules);

}  // namespace rad
