// renderPathTraced: the reference image, pixel tiles in parallel, each tile with its own random
// stream so the image does not depend on the thread count.
#include <radiosity/error.h>
#include <radiosity/path_tracer.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <chrono>

#include "geometry/sampling.h"
#include "render/camera_rays.h"
#include "render/path_integrator.h"
#include "render/path_tracer_settings.h"
#include "render/progress_ticker.h"

namespace rad {

namespace {

constexpr int kTileSize = 16;

// Samples between two questions to the progress callback: at a million samples a pixel takes
// seconds, and Ctrl-C must stop the render within one.
constexpr int kSamplesBetweenPolls = 1024;

void renderTile(const PathIntegrator& integrator, const PinholeCamera& camera,
                const PathTracerSettings& settings, int tile, int tilesX, Image& image,
                ProgressTicker& ticker) {
  Rng rng(settings.seed, uint64_t(tile));
  const int x0 = (tile % tilesX) * kTileSize, y0 = (tile / tilesX) * kTileSize;
  const int x1 = std::min(x0 + kTileSize, image.width);
  const int y1 = std::min(y0 + kTileSize, image.height);
  const float weight = 1.0f / float(settings.samplesPerPixel);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      Color sum(0.0f);
      for (int s = 0; s < settings.samplesPerPixel; ++s) {
        if (s % kSamplesBetweenPolls == kSamplesBetweenPolls - 1 && ticker.pollCancelled()) return;
        const Vec2 offset = uniformSquare(rng);
        sum += integrator.radiance(camera.ray(x, y, offset), rng);
      }
      image.at(x, y) = sum * weight;
      ticker.tick();
    }
}

}  // namespace

PathTracedImage renderPathTraced(const Scene& scene, const Camera& camera,
                                 const PathTracerSettings& settings,
                                 const ProgressCallback& progress) {
  validatePathTracerSettings(settings);
  return renderPathTraced(scene, RayCaster(scene), camera, settings, progress);
}

PathTracedImage renderPathTraced(const Scene& scene, const RayCaster& caster, const Camera& camera,
                                 const PathTracerSettings& settings,
                                 const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  validatePathTracerSettings(settings);
  const uint64_t raysBefore = caster.raysCast();
  const PinholeCamera pinhole(camera);
  const PathIntegrator integrator(scene, caster, settings.maxDepth);

  PathTracedImage result;
  result.image = Image(camera.width, camera.height);
  const int tilesX = (camera.width + kTileSize - 1) / kTileSize;
  const int tilesY = (camera.height + kTileSize - 1) / kTileSize;
  ProgressTicker ticker(progress, size_t(camera.width) * size_t(camera.height));
  tbb::parallel_for(tbb::blocked_range<int>(0, tilesX * tilesY), [&](const auto& range) {
    for (int tile = range.begin(); tile != range.end(); ++tile) {
      if (ticker.cancelled()) return;
      renderTile(integrator, pinhole, settings, tile, tilesX, result.image, ticker);
    }
  });
  ticker.throwIfCancelled();

  result.stats.rays = caster.raysCast() - raysBefore;
  result.stats.paths =
      uint64_t(camera.width) * uint64_t(camera.height) * uint64_t(settings.samplesPerPixel);
  result.stats.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace rad
