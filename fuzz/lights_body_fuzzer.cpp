// The body of the viewer's POST /api/lights (src/server/light_request.h) read against
// cornell-spot's lights and groups: accepted or an InputError, and what it accepts is a state a
// scene file could hold (finite positions within kMaxSceneCoordinate, unit directions,
// intensities times their group's scale in [0, kMaxLight]). Anything else is a finding.
#include <radiosity/light_groups.h>
#include <radiosity/scene_builder.h>
#include <radiosity/scene_loader.h>

#include <cmath>
#include <cstdlib>
#include <glm/gtx/component_wise.hpp>

#include "fuzz_support.h"
#include "server/light_request.h"

namespace {

struct Session {
  rad::Scene scene = rad::loadScene("cornell-spot");
  std::vector<rad::LightGroup> groups = rad::lightGroupsOf(scene, scene.lights);
  rad::LightState now{scene.lights, std::vector<rad::Color>(groups.size(), rad::Color(1.0f))};
};

const Session& session() {
  static const Session s;
  return s;
}

void check(bool holds) {
  if (!holds) std::abort();  // libFuzzer reports it with the input
}

void checkState(const rad::LightState& state, const Session& s) {
  check(state.lights.size() == s.now.lights.size() && state.scales.size() == s.groups.size());
  for (const rad::Light& l : state.lights) {
    check(glm::compMax(glm::abs(l.position)) <= rad::kMaxSceneCoordinate);
    check(std::abs(glm::length(l.direction) - 1.0f) < 1e-4f);
    check(rad::minComponent(l.intensity) >= 0.0f &&
          rad::maxComponent(l.intensity) <= rad::kMaxLight);
  }
  for (size_t g = 0; g < s.groups.size(); ++g)
    for (uint32_t i : s.groups[g].lights)
      check(rad::maxComponent(state.lights[i].intensity * state.scales[g]) <= rad::kMaxLight);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const Session& s = session();
  const std::string_view body(reinterpret_cast<const char*>(data), size);
  rad::fuzz::acceptingInputErrors([&] {
    const nlohmann::json request = rad::lightRequestJson(body);
    checkState(rad::lightStateAfter(request, s.now, {s.scene, s.groups, "", ""}), s);
    // A session that neither relights nor dims: any "lights" or "groups" refused.
    rad::lightStateAfter(request, s.now, {s.scene, s.groups, "no lights", "no groups"});
    check(!request.is_object() || (!request.contains("lights") && !request.contains("groups")));
  });
  return 0;
}
