// renderSurfaceRadiance: camera rays through Embree, each hit shaded by a SurfaceRadiance.
#include <radiosity/error.h>
#include <radiosity/surface_radiance.h>

#include "core/rng.h"
#include "geometry/sampling.h"
#include "render/camera_rays.h"
#include "render/progress_ticker.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace rad {

Image renderSurfaceRadiance(const Scene& scene, const Camera& camera, const SurfaceRadiance& radiance,
                            const SurfaceRenderSettings& settings, const ProgressCallback& progress) {
  if (settings.samplesPerPixel < 1)
    throw InputError("render", "samples per pixel must be at least 1");
  const PinholeCamera pinhole(camera);
  const RayCaster caster(scene);
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
          if (!hit.valid()) continue;
          sum += radiance.radiance({ray.origin + hit.distance * ray.direction, hit.geometricNormal,
                                    hit.triangle, hit.frontFace});
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
