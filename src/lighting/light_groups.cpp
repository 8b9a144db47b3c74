// Which emitters share a group, and the scales asked for them.
#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/light_groups.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <glm/gtc/constants.hpp>

namespace rad {

namespace {

LightGroup& groupNamed(std::vector<LightGroup>& groups, const std::string& name) {
  for (LightGroup& g : groups)
    if (g.name == name) return g;
  groups.push_back({name, {}, {}});
  return groups.back();
}

std::string ownGroupName(size_t light) {
  return fmt::format("light{}", light);
}

}  // namespace

std::vector<LightGroup> lightGroupsOf(const Scene& scene, std::span<const Light> lights) {
  std::vector<LightGroup> groups;
  for (uint32_t i = 0; i < lights.size(); ++i)
    groupNamed(groups, lights[i].group.empty() ? ownGroupName(i) : lights[i].group)
        .lights.push_back(i);
  for (uint32_t m = 0; m < scene.materials.size(); ++m)
    if (scene.materials[m].emits())
      groupNamed(groups, scene.materials[m].name).materials.push_back(m);
  // A light without a group must be alone in its own: another emitter that names its group
  // would silently join it.
  for (uint32_t i = 0; i < lights.size(); ++i) {
    if (!lights[i].group.empty()) continue;
    const LightGroup& own = groupNamed(groups, ownGroupName(i));
    if (own.lights.size() != 1 || !own.materials.empty())
      throw InputError(scene.name, fmt::format("light {} has no group, and its own group's name "
                                               "'{}' is taken by another emitter: give the light "
                                               "a \"group\"",
                                               i, own.name));
  }
  return groups;
}

Color scaledEmission(const Scene& scene, uint32_t material, std::span<const Color> scales) {
  const Color ke = scene.materials[material].emission;
  return material < scales.size() ? ke * scales[material] : ke;
}

Color groupPower(const Scene& scene, std::span<const Light> lights, const LightGroup& group) {
  Vec3d power(0.0);
  for (uint32_t i : group.lights) power += Vec3d(scene.lightPower(lights[i]));
  for (const Face& f : scene.faces) {
    const Material& m = scene.materials[f.material];
    if (std::find(group.materials.begin(), group.materials.end(), f.material) !=
        group.materials.end())
      power +=
          Vec3d(m.emission) * (glm::pi<double>() * (m.twoSided ? 2.0 : 1.0) * scene.coveredArea(f));
  }
  return Color(power);
}

void scaleEmitters(Scene& scene, std::span<const LightGroup> groups,
                   std::span<const Color> scales) {
  const LightState state{scene.lights, {scales.begin(), scales.end()}};
  const std::vector<Color> emission = state.emissionScales(scene, groups);
  scene.lights = state.effectiveLights(groups);
  for (size_t m = 0; m < emission.size(); ++m) scene.materials[m].emission *= emission[m];
}

std::vector<Light> LightState::effectiveLights(std::span<const LightGroup> groups) const {
  std::vector<Light> effective = lights;
  for (size_t g = 0; g < groups.size() && g < scales.size(); ++g)
    for (uint32_t i : groups[g].lights) effective[i].intensity *= scales[g];
  return effective;
}

std::vector<Color> LightState::emissionScales(const Scene& scene,
                                              std::span<const LightGroup> groups) const {
  std::vector<Color> emission(scene.materials.size(), Color(1.0f));
  for (size_t g = 0; g < groups.size() && g < scales.size(); ++g)
    for (uint32_t m : groups[g].materials) emission[m] = scales[g];
  return emission;
}

GroupScale parseGroupScale(std::string_view text) {
  auto fail = [&](const std::string& why) {
    throw InputError("--group",
                     fmt::format("'{}': {} (expected NAME=SCALE or NAME=r,g,b)", text, why));
  };
  const size_t eq = text.find('=');
  if (eq == std::string_view::npos) fail("no '='");
  GroupScale out{std::string(text.substr(0, eq)), Color(1.0f)};
  if (out.name.empty()) fail("no group name");
  std::vector<float> numbers;
  std::string_view rest = text.substr(eq + 1);
  while (true) {
    const size_t comma = rest.find(',');
    const std::string_view word = rest.substr(0, comma);
    float value = 0.0f;
    const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (error != std::errc() || end != word.data() + word.size() || word.empty())
      fail(fmt::format("'{}' is not a number", word));
    if (!(value >= 0.0f) || !std::isfinite(value))
      fail(fmt::format("scale {} must be finite and not negative", word));
    numbers.push_back(value);
    if (comma == std::string_view::npos) break;
    rest = rest.substr(comma + 1);
  }
  if (numbers.size() == 1)
    out.scale = Color(numbers[0]);
  else if (numbers.size() == 3)
    out.scale = Color(numbers[0], numbers[1], numbers[2]);
  else
    fail(fmt::format("{} numbers", numbers.size()));
  return out;
}

std::vector<Color> groupScalesFor(std::span<const LightGroup> groups,
                                  std::span<const GroupScale> scales) {
  std::vector<Color> out(groups.size(), Color(1.0f));
  for (const GroupScale& s : scales) {
    size_t g = 0;
    while (g < groups.size() && groups[g].name != s.name) ++g;
    if (g == groups.size()) {
      std::string names;
      for (const LightGroup& group : groups) names += (names.empty() ? "" : ", ") + group.name;
      throw InputError("--group", fmt::format("no light group '{}' (the scene's groups: {})",
                                              s.name, names.empty() ? "none" : names));
    }
    out[g] = s.scale;
  }
  return out;
}

}  // namespace rad
