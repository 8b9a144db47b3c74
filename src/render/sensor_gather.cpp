// sensorIrradiance: the light at sensor points from a surface solution. Three parts, each where
// it is known best: the analytic lights by one shadow ray each, the emitting triangles by their
// exact form factor times the share of them a point sees, and what the surfaces reflect by a
// stratified hemisphere of rays into the solution (its radiance less the emission the second
// part counted).
#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/light_groups.h>
#include <radiosity/sensors.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include "core/progress_ticker.h"
#include "core/rng.h"
#include "geometry/point_polygon_form_factor.h"
#include "geometry/sampling.h"
#include "lighting/direct_lighting.h"

namespace rad {

namespace {

// Emitting triangles beyond which their light is sampled by power (DirectLighting) rather than
// taken one by one: a form factor each costs about one shadow ray, so a point pays for a few
// hundred as much as for its hemisphere.
constexpr size_t kMaxAnalyticEmitters = 256;
constexpr int kMaxSensorRays = 1 << 20;

class SensorGather {
 public:
  SensorGather(const Scene& scene, const RayCaster& caster, const SurfaceRadiance& radiance,
               const SensorSettings& settings)
      : scene_(scene),
        caster_(caster),
        radiance_(radiance),
        direct_(scene, caster, radiance.directLights(), radiance.emissionScales()),
        settings_(settings),
        side_(strataPerSide(settings.hemisphereRays)) {
    for (uint32_t t = 0; t < scene.triangles.size(); ++t)
      if (maxComponent(emission(t)) > 0.0f) emitters_.push_back(t);
  }

  Color operator()(const SensorPoint& sensor, Rng& rng) const {
    const Vec3 n = glm::normalize(sensor.normal);
    return direct_.fromLights(sensor.position, n) + fromEmitters(sensor.position, n, rng) +
           reflected(sensor.position, n, rng);
  }

 private:
  // Ke of a triangle's material at its light group's scale (a texture multiplies it).
  Color emission(uint32_t triangle) const {
    return scaledEmission(scene_, scene_.faceOf(triangle).material, radiance_.emissionScales());
  }
  Color emissionAt(const SurfaceHit& hit) const {
    if (!hit.frontFace && !scene_.materialOf(hit.triangle).twoSided) return Color(0.0f);
    return emission(hit.triangle) *
           scene_.textureAt(scene_.materialOf(hit.triangle).emissionTexture, hit.triangle,
                            hit.barycentric);
  }

  Color fromEmitters(const Vec3& p, const Vec3& n, Rng& rng) const {
    Color sum(0.0f);
    if (emitters_.size() <= kMaxAnalyticEmitters) {
      for (uint32_t t : emitters_) sum += fromEmitter(t, p, n, rng);
      return sum;
    }
    const int samples = side_ * side_;
    for (int s = 0; s < samples; ++s) sum += direct_.sampleEmitters(p, n, rng);
    return sum / float(samples);
  }

  // pi Ke F (docs/references.md 1(f): F exact for the unoccluded triangle), times the share of
  // the triangle seen from p weighted by the form factor's kernel cos cos / d^2 (exact when all
  // or none of it is seen), the emission texture read where the samples fall.
  Color fromEmitter(uint32_t t, const Vec3& p, const Vec3& n, Rng& rng) const {
    const UVec3& tri = scene_.triangles[t];
    const Vec3 v0 = scene_.positions[tri.x], v1 = scene_.positions[tri.y],
               v2 = scene_.positions[tri.z];
    const Vec3 front = scene_.triangleNormal(t);
    const bool facesP = glm::dot(p - v0, front) > 0.0f;
    if (!facesP && !scene_.materialOf(t).twoSided) return Color(0.0f);
    const Vec3d polygon[3] = {Vec3d(v0), facesP ? Vec3d(v1) : Vec3d(v2),
                              facesP ? Vec3d(v2) : Vec3d(v1)};
    const double f = pointPolygonFormFactor(Vec3d(p), Vec3d(n), polygon);
    if (!(f > 0.0)) return Color(0.0f);
    const int side = strataPerSide(settings_.emitterSamples);
    Color seen(0.0f);
    double total = 0.0;
    for (int s = 0; s < side * side; ++s) {
      const Vec2 b = sampleUniformTriangle(sampleStratum(s, side, rng));
      const Vec3 x = (1.0f - b.x - b.y) * v0 + b.x * v1 + b.y * v2;
      const Vec3 d = x - p;
      const float d2 = glm::dot(d, d);
      const float w = std::max(0.0f, glm::dot(n, d)) * std::abs(glm::dot(front, d)) / (d2 * d2);
      if (!(w > 0.0f)) continue;
      total += w;
      if (direct_.visible(p, n, x)) seen += w * emissionAt({x, front, t, facesP, b});
    }
    if (!(total > 0.0)) return Color(0.0f);
    return float(glm::pi<double>() * f / total) * seen;
  }

  // pi times the mean radiance the surfaces reflect toward p, over cosine-weighted rays one in
  // each cell of a side x side grid of the hemisphere (their emission is fromEmitters').
  Color reflected(const Vec3& p, const Vec3& n, Rng& rng) const {
    const int count = side_ * side_;
    std::vector<Ray> rays(static_cast<size_t>(count));
    std::vector<Hit> hits(rays.size());
    const Vec3 origin = p + direct_.rayOffset(p) * n;
    for (int s = 0; s < count; ++s) {
      rays[size_t(s)].origin = origin;
      rays[size_t(s)].direction = toWorld(sampleCosineHemisphere(sampleStratum(s, side_, rng)), n);
    }
    caster_.intersect(rays, hits);
    Color sum(0.0f);
    for (size_t s = 0; s < rays.size(); ++s) {
      const Hit& h = hits[s];
      if (!h.valid()) continue;
      const SurfaceHit at{origin + h.distance * rays[s].direction, h.geometricNormal, h.triangle,
                          h.frontFace, h.barycentric};
      sum += glm::max(radiance_.radiance(at) - emissionAt(at), Color(0.0f));
    }
    return glm::pi<float>() * sum / float(count);
  }

  const Scene& scene_;
  const RayCaster& caster_;
  const SurfaceRadiance& radiance_;
  DirectLighting direct_;
  SensorSettings settings_;
  int side_;
  std::vector<uint32_t> emitters_;
};

}  // namespace

void validateSensorSettings(const SensorSettings& settings, const std::string& source) {
  if (settings.hemisphereRays < 1 || settings.hemisphereRays > kMaxSensorRays)
    throw InputError(source, fmt::format("sensor rays {} out of range [1, {}]",
                                         settings.hemisphereRays, kMaxSensorRays));
  if (settings.emitterSamples < 1 || settings.emitterSamples > kMaxSensorRays)
    throw InputError(source, fmt::format("emitter samples {} out of range [1, {}]",
                                         settings.emitterSamples, kMaxSensorRays));
}

std::vector<Color> sensorIrradiance(const Scene& scene, const RayCaster& caster,
                                    const SurfaceRadiance& radiance,
                                    std::span<const SensorPoint> points,
                                    const SensorSettings& settings,
                                    const ProgressCallback& progress) {
  validateSensorSettings(settings, "sensors");
  for (size_t i = 0; i < points.size(); ++i)
    if (!(glm::length(points[i].normal) > 0.0f) || !std::isfinite(glm::length(points[i].normal)) ||
        !std::isfinite(glm::length(points[i].position)))
      throw InputError("sensors", fmt::format("point {}: a finite position and a non-zero normal "
                                              "expected",
                                              i));
  const SensorGather gather(scene, caster, radiance, settings);
  std::vector<Color> irradiance(points.size(), Color(0.0f));
  ProgressTicker ticker(progress, points.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size()), [&](const auto& range) {
    for (size_t i = range.begin(); i != range.end(); ++i) {
      if (ticker.cancelled()) return;
      Rng rng(settings.seed, uint64_t(i));
      irradiance[i] = gather(points[i], rng);
      ticker.tick();
    }
  });
  ticker.throwIfCancelled();
  return irradiance;
}

}  // namespace rad
