#include "patch/patch_light_injection.h"

#include <array>
#include <cmath>
#include <glm/gtc/constants.hpp>

#include "patch/patch_quadrature.h"

namespace rad {

namespace {

// False only where no point of the patch (a planar polygon inside the sphere about `centre` of
// `radius`) can get light: the light lies behind its plane, or the spot's cone clears the sphere.
// What lets a moved spot cost the rays of its beam's patches only.
bool mayReach(const Light& light, const Vec3& centre, const Vec3& normal, float radius) {
  if (!light.positional()) return glm::dot(normal, light.direction) < 0.0f;
  const Vec3 v = centre - light.position;
  if (!(glm::dot(normal, -v) > 0.0f)) return false;
  if (light.type != LightType::Spot) return true;
  const float distance = glm::length(v);
  if (!(distance > radius)) return true;
  const float fromAxis =
      std::acos(std::clamp(glm::dot(v / distance, light.direction), -1.0f, 1.0f));
  const float seen = std::asin(radius / distance);
  return fromAxis - seen < glm::radians(light.outerAngleDeg) * 1.0001f;
}

}  // namespace

PatchLight lightOnPatch(const PatchMesh& mesh, uint32_t patch, const DirectLighting& direct,
                        const Light& light, int points) {
  const Patch& p = mesh.patches()[patch];
  std::array<Vec3, 4> corners;
  const int n = mesh.corners(patch, corners);
  float radius = 0.0f;
  for (int k = 0; k < n; ++k) radius = std::max(radius, glm::length(corners[k] - p.centroid));
  PatchLight out;
  if (!mayReach(light, p.centroid, p.normal, radius * 1.001f)) return out;
  std::vector<QuadraturePoint> at = coveredMidpointRule(mesh, patch, points);
  const size_t quadrature = at.size();
  for (int k = 0; k < n; ++k) at.push_back({corners[k] + 0.02f * (p.centroid - corners[k]), 0.0});
  Vec3d sum(0.0);
  bool lit = false, dark = false;
  for (size_t i = 0; i < at.size(); ++i) {
    const Color e = direct.fromLight(light, at[i].position, p.normal);
    (maxComponent(e) > 0.0f ? lit : dark) = true;
    if (i < quadrature) sum += at[i].weight * Vec3d(e);
  }
  out.edgeInside = lit && dark;
  out.direct = Color(sum);
  return out;
}

PatchLight lightOnPatch(const PatchMesh& mesh, uint32_t patch, const DirectLighting& direct,
                        int points) {
  PatchLight out;
  for (const Light& light : direct.lights())
    out += lightOnPatch(mesh, patch, direct, light, points);
  return out;
}

}  // namespace rad
