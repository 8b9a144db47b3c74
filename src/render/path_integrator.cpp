// Unidirectional path tracing of Lambertian surfaces with next-event estimation (Kajiya, "The
// Rendering Equation", SIGGRAPH 1986; Pharr, Jakob and Humphreys, "Physically Based Rendering",
// 4th ed., ch. 13). At every vertex: one emissive-triangle sample chosen by power and every
// analytic light; a cosine-weighted bounce. Emissive triangles are reached both ways and
// combined by the power heuristic (Veach and Guibas, "Optimally Combining Sampling Techniques
// for Monte Carlo Rendering", SIGGRAPH 1995), which keeps each contribution bounded where
// surfaces meet (area sampling alone has unbounded variance at edges, cos cos / d^2 -> inf).
// Russian roulette after the third vertex (Arvo and Kirk, "Particle Transport and Image
// Synthesis", SIGGRAPH 1990).
#include "render/path_integrator.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>

#include "geometry/sampling.h"

namespace rad {

namespace {

constexpr int kRouletteDepth = 3;
constexpr float kMaxSurvival = 0.95f;
// Float positions near magnitude m are good to about 6e-8 m; stay well above that.
constexpr float kRelativeOffset = 1e-5f;

float maxAbs(const Vec3& v) {
  return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

float powerHeuristic(float pdf, float otherPdf) {
  const float a = pdf * pdf, b = otherPdf * otherPdf;
  return a > 0.0f ? a / (a + b) : 0.0f;
}

}  // namespace

PathIntegrator::PathIntegrator(const Scene& scene, const RayCaster& caster, int maxDepth)
    : scene_(&scene), caster_(&caster), emitters_(scene), maxDepth_(maxDepth) {
  const Bounds b = scene.bounds();
  sceneExtent_ = b.empty() ? 1.0f : std::max(b.diagonal(), std::max(maxAbs(b.min), maxAbs(b.max)));
  if (!(sceneExtent_ > 0.0f)) sceneExtent_ = 1.0f;
}

float PathIntegrator::offset(const Vec3& p) const {
  return kRelativeOffset * (maxAbs(p) + sceneExtent_);
}

bool PathIntegrator::visible(const Vec3& p, const Vec3& n, const Vec3& target) const {
  Ray r;
  r.origin = p + offset(p) * n;
  const Vec3 d = target - r.origin;
  const float distance = glm::length(d);
  r.direction = d / distance;
  r.tFar = distance - offset(target);
  if (!(r.tFar > 0.0f)) return true;
  return !caster_->occluded(r);
}

Color PathIntegrator::directIntegral(const Vec3& p, const Vec3& n, bool misWeighted,
                                     Rng& rng) const {
  Color sum(0.0f);
  if (!emitters_.empty()) {
    const float choose = rng.uniform();
    const Vec2 position = uniformSquare(rng);
    const EmitterSample s = emitters_.sample(choose, position);
    const Vec3 d = s.point - p;
    const float distance2 = glm::dot(d, d);
    if (distance2 > 0.0f) {
      const Vec3 w = d / std::sqrt(distance2);
      const float cosReceiver = glm::dot(n, w);
      float cosEmitter = -glm::dot(s.normal, w);
      if (s.twoSided) cosEmitter = std::abs(cosEmitter);
      if (cosReceiver > 0.0f && cosEmitter > 0.0f && visible(p, n, s.point)) {
        const float pdfSolidAngle = s.pdfArea * distance2 / cosEmitter;
        const float weight =
            misWeighted ? powerHeuristic(pdfSolidAngle, cosReceiver * glm::one_over_pi<float>())
                        : 1.0f;
        sum += s.emission * (weight * cosReceiver / pdfSolidAngle);
      }
    }
  }
  for (const Light& light : scene_->lights) {
    const Vec3 d = light.position - p;
    const float distance2 = glm::dot(d, d);
    if (!(distance2 > 0.0f)) continue;
    const Vec3 w = d / std::sqrt(distance2);
    const float cosReceiver = glm::dot(n, w);
    if (!(cosReceiver > 0.0f)) continue;
    const Color intensity = light.intensityToward(-w);
    if (!(maxComponent(intensity) > 0.0f) || !visible(p, n, light.position)) continue;
    sum += intensity * (cosReceiver / distance2);
  }
  return sum;
}

Ray PathIntegrator::bounce(const Vec3& p, const Vec3& n, float& pdf, Rng& rng) const {
  const Vec2 u = uniformSquare(rng);
  const Vec3 local = sampleCosineHemisphere(u);
  pdf = local.z * glm::one_over_pi<float>();
  Ray r;
  r.origin = p + offset(p) * n;
  r.direction = glm::normalize(toWorld(local, n));
  return r;
}

Color PathIntegrator::trace(Ray ray, float bouncePdf, int firstDepth, Rng& rng) const {
  Color radiance(0.0f), throughput(1.0f);
  for (int depth = firstDepth; depth < maxDepth_; ++depth) {
    const Hit hit = caster_->intersect(ray);
    if (!hit.valid()) break;
    const Material& m = scene_->materialOf(hit.triangle);
    // A one-sided surface seen from behind absorbs everything and emits nothing.
    if (!hit.frontFace && !m.twoSided) break;
    if (bouncePdf < 0.0f) {
      radiance += throughput * m.emission;
    } else if (m.emits()) {
      const float cosEmitter = std::abs(glm::dot(hit.geometricNormal, ray.direction));
      const float lightPdf =
          emitters_.pdfArea(hit.triangle) * hit.distance * hit.distance / cosEmitter;
      radiance += throughput * m.emission * powerHeuristic(bouncePdf, lightPdf);
    }
    const Vec3 n = hit.frontFace ? hit.geometricNormal : -hit.geometricNormal;
    const UVec3& tri = scene_->triangles[hit.triangle];
    const Vec2 b = hit.barycentric;
    const Vec3 p = (1.0f - b.x - b.y) * scene_->positions[tri.x] + b.x * scene_->positions[tri.y] +
                   b.y * scene_->positions[tri.z];
    throughput *= m.rho;
    if (!(maxComponent(throughput) > 0.0f)) break;
    // The last vertex has no bounce to find emitters, so its light sample takes full weight.
    const bool last = depth + 1 >= maxDepth_;
    radiance += throughput * directIntegral(p, n, !last, rng) * glm::one_over_pi<float>();
    if (last) break;
    if (depth >= kRouletteDepth) {
      const float survival = std::min(kMaxSurvival, maxComponent(throughput));
      if (rng.uniform() >= survival) break;
      throughput /= survival;
    }
    ray = bounce(p, n, bouncePdf, rng);
  }
  return radiance;
}

Color PathIntegrator::radiance(const Ray& ray, Rng& rng) const {
  return trace(ray, -1.0f, 0, rng);
}

Color PathIntegrator::irradiance(const Vec3& p, const Vec3& n, Rng& rng) const {
  const bool bounces = maxDepth_ > 1;
  Color h = directIntegral(p, n, bounces, rng);
  if (bounces) {
    float pdf = 0.0f;
    const Ray r = bounce(p, n, pdf, rng);
    h += glm::pi<float>() * trace(r, pdf, 1, rng);
  }
  return h;
}

}  // namespace rad
