#pragma once
// Light groups: sets of emitters whose light is solved apart, so that a solution can dim, tint or
// switch off each set afterwards with its full multi-bounce answer and no new solve. Radiosity is
// linear in the emitted light: with B_g the solution of group g alone, scaling group g's
// emitters by s_g gives B = sum_g s_g B_g.

#include <radiosity/scene.h>

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rad {

/// One group: the lights that name it and the emitting materials named after it.
struct LightGroup {
  std::string name;
  std::vector<uint32_t> lights;     ///< indices into the lights solved with
  std::vector<uint32_t> materials;  ///< indices into the scene's materials (emitting ones)
};

/// The groups of `lights` and of the scene's emitting materials, in order of first appearance:
/// a light's group is its `group`, else a group of its own named "light<i>" (i its index); an
/// emitting material's group is named after the material. Emitters of the same name share one
/// group (a lamp's bulb light and its glowing shade). Throws InputError where a light's own name
/// "light<i>" is taken by another group.
std::vector<LightGroup> lightGroupsOf(const Scene& scene, std::span<const Light> lights);

/// Material `material`'s emission (Ke) times its factor in `scales` (one per material: a light
/// group's scale; none, or a material past its end: 1). What every picture and sampler shows of
/// a dimmed glowing surface.
Color scaledEmission(const Scene& scene, uint32_t material, std::span<const Color> scales);

/// The power (W) group `group` of `lights` and the scene's materials emits at scale 1.
Color groupPower(const Scene& scene, std::span<const Light> lights, const LightGroup& group);

/// Scales the emitters of `scene` in place, each group's (of `groups`, made for scene.lights)
/// by its `scales` entry: the scene a solver without groups (the path tracer) then solves to the
/// same answer as a combination of groups.
void scaleEmitters(Scene& scene, std::span<const LightGroup> groups, std::span<const Color> scales);

/// What `--group NAME=SCALE` or `NAME=r,g,b` asks: a group's light times `scale` (0 switches it
/// off).
struct GroupScale {
  std::string name;
  Color scale{1.0f};
};
/// Parses "NAME=SCALE" or "NAME=r,g,b" (non-negative, finite numbers). Throws InputError naming
/// `text` and what was expected.
GroupScale parseGroupScale(std::string_view text);
/// A scale per group of `groups`: the one `scales` gives it, else 1. Throws InputError for a
/// name that is no group's, listing the groups.
std::vector<Color> groupScalesFor(std::span<const LightGroup> groups,
                                  std::span<const GroupScale> scales);

/// The lights as a front end sets them, each at its own intensity, and each light group's scale:
/// what animate and the viewer keep, and turn into what a solve or relight is given.
struct LightState {
  std::vector<Light> lights;
  std::vector<Color> scales;  ///< per group of the groups it is used with (1: as set)

  /// The lights, each times its group's scale (groups: lightGroupsOf the scene and `lights`).
  std::vector<Light> effectiveLights(std::span<const LightGroup> groups) const;
  /// Per material of `scene`, its group's scale (1 for materials in no group): the emission
  /// scales of a relight.
  std::vector<Color> emissionScales(const Scene& scene, std::span<const LightGroup> groups) const;
};

}  // namespace rad
