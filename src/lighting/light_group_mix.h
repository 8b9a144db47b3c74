#pragma once
// What a solution that keeps its light groups apart holds besides its arrays: the groups, each
// one's emitters, and the scales it combines them with. The patch and voxel methods keep a
// per-group array of their elements' irradiance and combine them here, so that rescaling a group
// is a weighted sum, not a solve.

#include <radiosity/light_groups.h>
#include <radiosity/scene.h>

#include <span>
#include <vector>

namespace rad {

class LightGroupMix {
 public:
  /// No lights, no groups.
  LightGroupMix() = default;
  /// The emitters of `scene` and `lights`, solved together (apart() false) or by group.
  LightGroupMix(const Scene& scene, std::span<const Light> lights, bool apart);

  /// True when the groups are solved apart.
  bool apart() const { return !groups_.empty(); }
  /// The groups (empty when not apart).
  std::span<const LightGroup> groups() const { return groups_; }
  /// Group g's lights alone.
  std::vector<Light> lightsOf(size_t g) const;
  /// Material m's emission (Ke) in group g's solve: its own if it is one of the group's
  /// emitters, else none.
  Color groupEmission(const Scene& scene, size_t g, uint32_t material) const;

  /// Sets a scale per group (RGB, finite, not negative). Throws std::invalid_argument for a
  /// count that is not the groups' or a bad value.
  void setScales(std::span<const Color> scales);
  std::span<const Color> scales() const { return scales_; }
  /// The lights solved with, each times its group's scale: what the renderer adds per pixel.
  std::span<const Light> lights() const { return scaledLights_; }
  /// A factor per scene material on the emission shown, for a solution solved together whose
  /// emitters were dimmed another way (a relighter's); empty: none. Not for groups kept apart.
  void setEmissionScales(std::span<const Color> scales);
  /// Per scene material, its group's scale (empty when not apart: the scene's own emission).
  std::span<const Color> emissionScales() const { return materialScales_; }
  /// Material m's emission as the solution shows it (Ke times its group's scale).
  Color emission(const Scene& scene, uint32_t material) const;
  /// sum_g scale_g perGroup[g][i], for every element i.
  std::vector<Color> combine(const std::vector<std::vector<Color>>& perGroup) const;

 private:
  std::vector<LightGroup> groups_;
  std::vector<Light> lights_, scaledLights_;
  std::vector<Color> scales_, materialScales_;
};

}  // namespace rad
