// renderSurfaceRadiance: camera rays through Embree, each hit shaded by a SurfaceRadiance.
#include <radiosity/error.h>
#include <radiosity/light_groups.h>
#include <radiosity/surface_radiance.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <glm/gtc/constants.hpp>

#include "core/progress_ticker.h"
#include "core/rng.h"
#include "geometry/sampling.h"
#include "lighting/direct_lighting.h"
#include "render/camera_rays.h"

namespace rad {

namespace {

// Ke + rho (D + H_ind) / pi at a hit: the solution's indirect light, the direct light computed
// here with shadow rays (DirectLighting, the physics the path tracer uses).
class PerPixelDirectShading {
 public:
  // A sky gets as many rays a hit as the emitters get samples.
  PerPixelDirectShading(const Scene& scene, const RayCaster& caster,
                        const SurfaceRadiance& radiance, int emitterSamples, bool irradiance)
      : scene_(scene),
        direct_(scene, caster, radiance.directLights(), radiance.emissionScales(), emitterSamples),
        radiance_(radiance),
        emitterSamples_(emitterSamples),
        irradiance_(irradiance) {}

  Color operator()(const SurfaceHit& hit, Rng& rng) const {
    const Material& m = scene_.materialOf(hit.triangle);
    if (!hit.frontFace && !m.twoSided) return Color(0.0f);
    const Vec3 n = hit.frontFace ? hit.normal : -hit.normal;
    Color h = radiance_.indirectIrradiance(hit) + direct_.fromLights(hit.point, n);
    if (direct_.hasEmitters()) {
      Color emitted(0.0f);
      for (int s = 0; s < emitterSamples_; ++s)
        emitted += direct_.sampleEmitters(hit.point, n, rng);
      h += emitted / float(emitterSamples_);
    }
    if (irradiance_) return h;
    // (the scales cover the solution's own materials; a scene with objects placed has more)
    const Color ke =
        scaledEmission(scene_, scene_.faceOf(hit.triangle).material, radiance_.emissionScales()) *
        scene_.textureAt(m.emissionTexture, hit.triangle, hit.barycentric);
    return ke + scene_.reflectanceAt(hit.triangle, hit.barycentric) * h * glm::one_over_pi<float>();
  }

  /// What a camera ray that leaves the scene along `w` sees: the sky the solution was lit by
  /// (at its group's scale), or the scene's where the solution names no lights.
  Color escaped(const Vec3& w) const {
    return radiance_.directLights().empty() ? skyRadiance(scene_.lights, w)
                                            : direct_.skyRadiance(w);
  }

 private:
  const Scene& scene_;
  DirectLighting direct_;
  const SurfaceRadiance& radiance_;
  int emitterSamples_;
  bool irradiance_;
};

}  // namespace

Image renderSurfaceRadiance(const Scene& scene, const Camera& camera,
                            const SurfaceRadiance& radiance, const SurfaceRenderSettings& settings,
                            const ProgressCallback& progress) {
  return renderSurfaceRadiance(scene, RayCaster(scene), camera, radiance, settings, progress);
}

Image renderSurfaceRadiance(const Scene& scene, const RayCaster& caster, const Camera& camera,
                            const SurfaceRadiance& radiance, const SurfaceRenderSettings& settings,
                            const ProgressCallback& progress) {
  if (settings.samplesPerPixel < 1)
    throw InputError("render", "samples per pixel must be at least 1");
  if (settings.emitterSamples < 1) throw InputError("render", "emitter samples must be at least 1");
  const PinholeCamera pinhole(camera);
  const bool perPixel =
      settings.direct == DirectLightMode::PerPixel && radiance.hasIndirectIrradiance();
  if (settings.irradiance && !perPixel)
    throw InputError("render",
                     "a picture of the irradiance needs per-pixel direct light (a "
                     "solution that keeps its direct light apart)");
  const PerPixelDirectShading shade(scene, caster, radiance, settings.emitterSamples,
                                    settings.irradiance);
  Image image(camera.width, camera.height);
  ProgressTicker ticker(progress, size_t(camera.height));
  tbb::parallel_for(tbb::blocked_range<int>(0, camera.height), [&](const auto& rows) {
    for (int y = rows.begin(); y != rows.end(); ++y) {
      if (ticker.cancelled()) return;
      Rng rng(settings.seed, uint64_t(y));
      for (int x = 0; x < camera.width; ++x) {
        Color sum(0.0f);
        for (int s = 0; s < settings.samplesPerPixel; ++s) {
          const Ray ray = pinhole.ray(x, y, pixelSample(s, settings.samplesPerPixel, rng));
          const Hit hit = caster.intersect(ray);
          if (!hit.valid()) {
            // The sky where a picture of radiance looks out; no surface, no irradiance.
            if (!settings.irradiance) sum += shade.escaped(ray.direction);
            continue;
          }
          const SurfaceHit at{ray.origin + hit.distance * ray.direction, hit.geometricNormal,
                              hit.triangle, hit.frontFace, hit.barycentric};
          sum += perPixel ? shade(at, rng) : radiance.radiance(at);
        }
        image.at(x, y) = sum / float(settings.samplesPerPixel);
      }
      ticker.tick();
    }
  });
  ticker.throwIfCancelled();
  return image;
}

}  // namespace rad
