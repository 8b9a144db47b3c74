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
  if (light.type == LightType::Sky) return true;  // a ray toward no sky costs nothing
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

// A sky's D over the quadrature points, its rays stratified together (DirectLighting::skyOver).
// No edge test: the sky's light is soft, and its rays' noise would read as edges.
Color skyOnPatch(const DirectLighting& direct, const Light& sky,
                 std::span<const QuadraturePoint> at, const Vec3& normal) {
  std::vector<Vec3> points(at.size());
  std::vector<double> weights(at.size());
  for (size_t i = 0; i < at.size(); ++i) {
    points[i] = at[i].position;
    weights[i] = at[i].weight;
  }
  return direct.skyOver(sky, points, weights, normal);
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
  if (light.type == LightType::Sky) return {skyOnPatch(direct, light, at, p.normal), false};
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
