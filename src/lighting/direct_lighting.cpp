// Direct illumination by next-event estimation (Pharr, Jakob and Humphreys, "Physically Based
// Rendering", 4th ed., sections 12.1-12.2 and 13.4): analytic lights by one shadow ray each,
// emissive triangles by area sampling in proportion to power, combined with a cosine bounce by
// the power heuristic (Veach and Guibas, SIGGRAPH 1995) when the caller also bounces.
#include "lighting/direct_lighting.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <limits>

#include "geometry/sampling.h"

namespace rad {

namespace {

// Float positions near magnitude m are good to about 6e-8 m; stay well above that.
constexpr float kRelativeOffset = 1e-5f;

float maxAbs(const Vec3& v) {
  return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

}  // namespace

DirectLighting::DirectLighting(const Scene& scene, const RayCaster& caster)
    : DirectLighting(scene, caster, scene.lights) {}

DirectLighting::DirectLighting(const Scene& scene, const RayCaster& caster,
                               std::span<const Light> lights)
    : DirectLighting(scene, caster, lights, {}) {}

DirectLighting::DirectLighting(const Scene& scene, const RayCaster& caster,
                               std::span<const Light> lights, std::span<const Color> emissionScales)
    : caster_(&caster), lights_(lights), emitters_(scene, emissionScales) {
  const Bounds b = scene.bounds();
  sceneExtent_ = b.empty() ? 1.0f : std::max(b.diagonal(), std::max(maxAbs(b.min), maxAbs(b.max)));
  if (!(sceneExtent_ > 0.0f)) sceneExtent_ = 1.0f;
}

float DirectLighting::rayOffset(const Vec3& p) const {
  return kRelativeOffset * (maxAbs(p) + sceneExtent_);
}

bool DirectLighting::visible(const Vec3& p, const Vec3& n, const Vec3& target,
                             float stopShort) const {
  Ray r;
  r.origin = p + rayOffset(p) * n;
  const Vec3 d = target - r.origin;
  const float distance = glm::length(d);
  r.direction = d / distance;
  r.tFar = distance - std::max(rayOffset(target), stopShort);
  if (!(r.tFar > 0.0f)) return true;
  return !caster_->occluded(r);
}

bool DirectLighting::visibleToward(const Vec3& p, const Vec3& n, const Vec3& w) const {
  Ray r;
  r.origin = p + rayOffset(p) * n;
  r.direction = w;
  r.tFar = std::numeric_limits<float>::infinity();
  return !caster_->occluded(r);
}

Color DirectLighting::fromLight(const Light& light, const Vec3& p, const Vec3& n) const {
  if (!light.positional()) {  // parallel rays from beyond the scene: E cos(theta), unshadowed
    const Vec3 w = -light.direction;
    const float cosReceiver = glm::dot(n, w);
    if (!(cosReceiver > 0.0f) || !(maxComponent(light.intensity) > 0.0f) || !visibleToward(p, n, w))
      return Color(0.0f);
    return light.intensity * cosReceiver;
  }
  const Vec3 d = light.position - p;
  const float distance2 = glm::dot(d, d);
  if (!(distance2 > 0.0f)) return Color(0.0f);
  const Vec3 w = d / std::sqrt(distance2);
  const float cosReceiver = glm::dot(n, w);
  if (!(cosReceiver > 0.0f)) return Color(0.0f);
  const Color intensity = light.intensityToward(-w);
  if (!(maxComponent(intensity) > 0.0f) || !visible(p, n, light.position, light.radius))
    return Color(0.0f);
  return intensity * (cosReceiver / distance2);
}

Color DirectLighting::fromLights(const Vec3& p, const Vec3& n) const {
  Color sum(0.0f);
  for (const Light& light : lights_) sum += fromLight(light, p, n);
  return sum;
}

Color DirectLighting::sampleEmitters(const Vec3& p, const Vec3& n, Rng& rng,
                                     bool misWeighted) const {
  if (emitters_.empty()) return Color(0.0f);
  const float choose = rng.uniform();
  const Vec2 position = uniformSquare(rng);
  const EmitterSample s = emitters_.sample(choose, position);
  const Vec3 d = s.point - p;
  const float distance2 = glm::dot(d, d);
  if (!(distance2 > 0.0f)) return Color(0.0f);
  const Vec3 w = d / std::sqrt(distance2);
  const float cosReceiver = glm::dot(n, w);
  float cosEmitter = -glm::dot(s.normal, w);
  if (s.twoSided) cosEmitter = std::abs(cosEmitter);
  if (!(cosReceiver > 0.0f && cosEmitter > 0.0f) || !visible(p, n, s.point)) return Color(0.0f);
  const float pdfSolidAngle = s.pdfArea * distance2 / cosEmitter;
  const float weight =
      misWeighted ? powerHeuristic(pdfSolidAngle, cosReceiver * glm::one_over_pi<float>()) : 1.0f;
  return s.emission * (weight * cosReceiver / pdfSolidAngle);
}

}  // namespace rad
