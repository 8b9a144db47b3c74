// Radiosity pictures with the direct light taken per pixel (shadow rays at each camera ray's hit)
// and only the bounces from the solution, against a path-traced reference of the same view.
#include <gtest/gtest.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/path_tracer.h>
#include <radiosity/scene_loader.h>
#include <radiosity/surface_radiance.h>

#include <cmath>

namespace rad {
namespace {

struct ImageError {
  double meanBlock = 0.0;  ///< mean relative luminance error of 8 x 8 blocks
  double meanPixel = 0.0;  ///< mean relative luminance error of pixels
};

// Over the blocks and pixels brighter than 5% of the reference's mean (the open front of the
// box is black in both).
ImageError relativeError(const Image& image, const Image& reference) {
  double mean = 0.0;
  for (int y = 0; y < reference.height; ++y)
    for (int x = 0; x < reference.width; ++x) mean += luminance(reference.at(x, y));
  mean /= double(reference.width) * reference.height;
  ImageError e;
  int blocks = 0, pixels = 0;
  for (int by = 0; by + 8 <= reference.height; by += 8)
    for (int bx = 0; bx + 8 <= reference.width; bx += 8) {
      double a = 0.0, b = 0.0;
      for (int y = by; y < by + 8; ++y)
        for (int x = bx; x < bx + 8; ++x) {
          const double p = luminance(image.at(x, y)), r = luminance(reference.at(x, y));
          a += p;
          b += r;
          if (r > 0.05 * mean) {
            e.meanPixel += std::abs(p - r) / r;
            ++pixels;
          }
        }
      if (b > 0.05 * mean * 64) {
        e.meanBlock += std::abs(a - b) / b;
        ++blocks;
      }
    }
  e.meanBlock /= std::max(blocks, 1);
  e.meanPixel /= std::max(pixels, 1);
  return e;
}

// The patch solution's picture at 64 x 64, direct light per pixel and from the solution, each
// against the path tracer's (4,096 paths a pixel).
struct PictureErrors {
  ImageError perPixel, fromSolution;
};
PictureErrors patchPictureErrors(const std::string& sceneName, int refineLevels) {
  const Scene scene = loadScene(sceneName);
  Camera camera = scene.cameraOrDefault();
  camera.width = camera.height = 64;
  PathTracerSettings traced;
  traced.samplesPerPixel = 4096;
  const Image reference = renderPathTraced(scene, camera, traced).image;
  PatchRadiositySettings settings;
  settings.cacheDir.clear();
  settings.refineLevels = refineLevels;
  const PatchRadiosity solution(scene, settings);
  EXPECT_TRUE(solution.hasIndirectIrradiance());
  SurfaceRenderSettings render;
  render.samplesPerPixel = 16;
  PictureErrors e;
  e.perPixel = relativeError(renderSurfaceRadiance(scene, camera, solution, render), reference);
  render.direct = DirectLightMode::Solution;
  e.fromSolution = relativeError(renderSurfaceRadiance(scene, camera, solution, render), reference);
  return e;
}

// The Cornell box: measured 1.7% per block and 3.6% per pixel on average, the solution's own
// light 3.9% and 5.1%. At 256 x 256 against 16,384 paths: 1.63% and 2.75%, against 3.57% and
// 4.65%. At this size the reference's own noise adds to the pixels' error (its 8 x 8 blocks
// average it away), so the pixels are held to the picture taken from the solution, the blocks
// to the 2% target.
TEST(PerPixelDirect, CornellPatchPictureMatchesThePathTracer) {
  const PictureErrors e = patchPictureErrors("cornell", 0);
  EXPECT_LT(e.perPixel.meanBlock, 0.02);
  EXPECT_LT(e.perPixel.meanBlock, 0.7 * e.fromSolution.meanBlock);
  EXPECT_LT(e.perPixel.meanPixel, e.fromSolution.meanPixel);
}

// A spot's beam edge and the blocks' hard shadows stay sharp per pixel, where unrefined patches
// blur them over a patch: measured 1.9% per block against 4.1% from the solution (6.2% and 10.3%
// per pixel, most of it the reference's noise in the dim parts). With adaptive subdivision (the
// default, 2 levels) the solution alone comes to 0.9% here; at 128 x 128 against 8,192 paths
// per-pixel 1.89% / 4.71%, from the solution 2.09% / 5.51%.
TEST(PerPixelDirect, CornellSpotPictureMatchesThePathTracer) {
  const PictureErrors e = patchPictureErrors("cornell-spot", 0);
  EXPECT_LT(e.perPixel.meanBlock, 0.03);
  EXPECT_LT(e.perPixel.meanBlock, 0.6 * e.fromSolution.meanBlock);
  EXPECT_LT(e.perPixel.meanPixel, 0.8 * e.fromSolution.meanPixel);
}

}  // namespace
}  // namespace rad
