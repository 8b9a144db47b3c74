// Unidirectional path tracing of Lambertian surfaces with next-event estimation (Kajiya, "The
// Rendering Equation", SIGGRAPH 1986; Pharr, Jakob and Humphreys, "Physically Based Rendering",
// 4th ed., ch. 13). At every vertex: one emissive-triangle sample chosen by power and every
// analytic light; a cosine-weighted bounce, which brings the sky's radiance where it escapes.
// Emissive triangles are reached both ways and combined by the power heuristic (Veach and Guibas,
// "Optimally Combining Sampling Techniques for Monte Carlo Rendering", SIGGRAPH 1995), which keeps
// each contribution bounded where surfaces meet (area sampling alone has unbounded variance at
// edges, cos cos / d^2 -> inf). Russian roulette after the third vertex (Arvo and Kirk, "Particle
// Transport and Image Synthesis", SIGGRAPH 1990).
#include "render/path_integrator.h"

#include <algorithm>
#include <glm/gtc/constants.hpp>

#include "geometry/sampling.h"

namespace rad {

namespace {

constexpr int kRouletteDepth = 3;
constexpr float kMaxSurvival = 0.95f;

}  // namespace

PathIntegrator::PathIntegrator(const Scene& scene, const RayCaster& caster, int maxDepth)
    : scene_(&scene), caster_(&caster), direct_(scene, caster), maxDepth_(maxDepth) {}

Color PathIntegrator::directIntegral(const Vec3& p, const Vec3& n, bool misWeighted,
                                     Rng& rng) const {
  Color sum = direct_.sampleEmitters(p, n, rng, misWeighted);
  for (const Light& light : direct_.lights())
    if (light.type != LightType::Sky) sum += direct_.fromLight(light, p, n);
  // The sky is found by the bounce, a ray that leaves the scene; where none follows, by a ray
  // of its own: counted once either way.
  if (!misWeighted) sum += direct_.fromSky(p, n, rng, 1);
  return sum;
}

Ray PathIntegrator::bounce(const Vec3& p, const Vec3& n, float& pdf, Rng& rng) const {
  const Vec2 u = uniformSquare(rng);
  const Vec3 local = sampleCosineHemisphere(u);
  pdf = local.z * glm::one_over_pi<float>();
  Ray r;
  r.origin = p + direct_.rayOffset(p) * n;
  r.direction = glm::normalize(toWorld(local, n));
  return r;
}

Color PathIntegrator::trace(Ray ray, float bouncePdf, int firstDepth, Rng& rng) const {
  Color radiance(0.0f), throughput(1.0f);
  for (int depth = firstDepth; depth < maxDepth_; ++depth) {
    const Hit hit = caster_->intersect(ray);
    if (!hit.valid()) {
      radiance += throughput * direct_.skyRadiance(ray.direction);
      break;
    }
    const Material& m = scene_->materialOf(hit.triangle);
    // A one-sided surface seen from behind absorbs everything and emits nothing.
    if (!hit.frontFace && !m.twoSided) break;
    if (bouncePdf < 0.0f) {
      radiance += throughput * scene_->emissionAt(hit.triangle, hit.barycentric);
    } else if (m.emits()) {
      const float cosEmitter = std::abs(glm::dot(hit.geometricNormal, ray.direction));
      const float lightPdf =
          direct_.emitterPdfArea(hit.triangle) * hit.distance * hit.distance / cosEmitter;
      radiance += throughput * scene_->emissionAt(hit.triangle, hit.barycentric) *
                  powerHeuristic(bouncePdf, lightPdf);
    }
    const Vec3 n = hit.frontFace ? hit.geometricNormal : -hit.geometricNormal;
    const UVec3& tri = scene_->triangles[hit.triangle];
    const Vec2 b = hit.barycentric;
    const Vec3 p = (1.0f - b.x - b.y) * scene_->positions[tri.x] + b.x * scene_->positions[tri.y] +
                   b.y * scene_->positions[tri.z];
    throughput *= scene_->reflectanceAt(hit.triangle, b);
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

Color PathIntegrator::irradianceSeen(const Ray& ray, Rng& rng) const {
  const Hit hit = caster_->intersect(ray);
  if (!hit.valid()) return Color(0.0f);
  if (!hit.frontFace && !scene_->materialOf(hit.triangle).twoSided) return Color(0.0f);
  const Vec3 n = hit.frontFace ? hit.geometricNormal : -hit.geometricNormal;
  return irradiance(ray.origin + hit.distance * ray.direction, n, rng);
}

}  // namespace rad
