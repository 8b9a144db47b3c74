// Combining per-group solutions: linear in the scales.
#include "lighting/light_group_mix.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rad {

LightGroupMix::LightGroupMix(const Scene& scene, std::span<const Light> lights, bool apart)
    : lights_(lights.begin(), lights.end()), scaledLights_(lights_) {
  if (!apart) return;
  groups_ = lightGroupsOf(scene, lights);
  scales_.assign(groups_.size(), Color(1.0f));
  materialScales_.assign(scene.materials.size(), Color(1.0f));
}

std::vector<Light> LightGroupMix::lightsOf(size_t g) const {
  std::vector<Light> out;
  for (uint32_t i : groups_.at(g).lights) out.push_back(lights_[i]);
  return out;
}

Color LightGroupMix::groupEmission(const Scene& scene, size_t g, uint32_t material) const {
  const std::vector<uint32_t>& own = groups_.at(g).materials;
  return std::find(own.begin(), own.end(), material) != own.end()
             ? scene.materials[material].emission
             : Color(0.0f);
}

void LightGroupMix::setScales(std::span<const Color> scales) {
  if (scales.size() != groups_.size())
    throw std::invalid_argument(
        fmt::format("{} scales for {} light groups", scales.size(), groups_.size()));
  for (const Color& s : scales)
    if (!(minComponent(s) >= 0.0f) || !std::isfinite(maxComponent(s)))
      throw std::invalid_argument("a light group's scale must be finite and not negative");
  scales_.assign(scales.begin(), scales.end());
  for (size_t g = 0; g < groups_.size(); ++g) {
    for (uint32_t i : groups_[g].lights)
      scaledLights_[i].intensity = lights_[i].intensity * scales_[g];
    for (uint32_t m : groups_[g].materials) materialScales_[m] = scales_[g];
  }
}

void LightGroupMix::setEmissionScales(std::span<const Color> scales) {
  if (apart()) throw std::invalid_argument("emission scales of groups kept apart come from them");
  materialScales_.assign(scales.begin(), scales.end());
}

Color LightGroupMix::emission(const Scene& scene, uint32_t material) const {
  return scaledEmission(scene, material, materialScales_);
}

std::vector<Color> LightGroupMix::combine(const std::vector<std::vector<Color>>& perGroup) const {
  std::vector<Color> out(perGroup.empty() ? 0 : perGroup[0].size(), Color(0.0f));
  tbb::parallel_for(tbb::blocked_range<size_t>(0, out.size(), 4096), [&](const auto& r) {
    for (size_t g = 0; g < perGroup.size(); ++g)
      for (size_t i = r.begin(); i != r.end(); ++i) out[i] += scales_[g] * perGroup[g][i];
  });
  return out;
}

}  // namespace rad
