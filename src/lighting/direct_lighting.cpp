// Direct illumination by next-event estimation (Pharr, Jakob and Humphreys, "Physically Based
// Rendering", 4th ed., sections 12.1-12.2 and 13.4): analytic lights by one shadow ray each,
// emissive triangles by area sampling in proportion to power, combined with a cosine bounce by
// the power heuristic (Veach and Guibas, SIGGRAPH 1995) when the caller also bounces.
#include "lighting/direct_lighting.h"

#include <algorithm>
#include <cmath>
#include <cstring>
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
                               std::span<const Light> lights, std::span<const Color> emissionScales,
                               int skySamples)
    : caster_(&caster),
      lights_(lights),
      emitters_(scene, emissionScales),
      skySamples_(std::max(1, skySamples)) {
  for (const Light& light : lights_) hasSky_ = hasSky_ || light.type == LightType::Sky;
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

Color DirectLighting::skySample(const Light& sky, const Vec3& p, const Vec3& n, Vec2 u) const {
  const Vec3 w = glm::normalize(toWorld(sampleCosineHemisphere(u), n));
  const Color l = sky.intensityToward(-w);
  if (!(maxComponent(l) > 0.0f) || !visibleToward(p, n, w)) return Color(0.0f);
  return glm::pi<float>() * l;
}

Color DirectLighting::fromSky(const Vec3& p, const Vec3& n, Rng& rng, int samples) const {
  if (!hasSky_ || samples < 1) return Color(0.0f);
  Color sum(0.0f);
  for (int s = 0; s < samples; ++s) {
    const Vec2 u = stratifiedSample(s, samples, rng);
    for (const Light& light : lights_)
      if (light.type == LightType::Sky) sum += skySample(light, p, n, u);
  }
  return sum / float(samples);
}

Color skyRadiance(std::span<const Light> lights, const Vec3& w) {
  Color sum(0.0f);
  for (const Light& light : lights)
    if (light.type == LightType::Sky) sum += light.intensityToward(-w);
  return sum;
}

Color DirectLighting::skyRadiance(const Vec3& w) const {
  return hasSky_ ? rad::skyRadiance(lights_, w) : Color(0.0f);
}

Color DirectLighting::skyOver(const Light& sky, std::span<const Vec3> points,
                              std::span<const double> weights, const Vec3& n) const {
  if (points.empty()) return Color(0.0f);
  const Vec3 key[2] = {points[0], n};
  uint64_t bits[3] = {};
  std::memcpy(bits, key, sizeof key);
  Rng rng(splitMix64(bits[0] ^ splitMix64(bits[1])), splitMix64(bits[2]));
  const int q = int(points.size()), count = q * std::max(1, skySamples_ / q);
  const std::vector<int> owner = randomPermutation(count, rng);
  Vec3d sum(0.0);
  for (int s = 0; s < count; ++s) {
    const int i = owner[size_t(s)] % q;
    const Color e = skySample(sky, points[size_t(i)], n, stratifiedSample(s, count, rng));
    sum += double(q) * weights[size_t(i)] * Vec3d(e);
  }
  return Color(sum / double(count));
}

Color DirectLighting::fromLight(const Light& light, const Vec3& p, const Vec3& n) const {
  if (light.type == LightType::Sky) {
    const double whole = 1.0;
    return skyOver(light, {&p, 1}, {&whole, 1}, n);
  }
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
