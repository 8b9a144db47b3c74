#pragma once
// The one interface every radiosity method ends in: the outgoing radiance at a surface point.
// The renderer, the exporters and the probes only know this interface.

#include <radiosity/image.h>
#include <radiosity/progress.h>
#include <radiosity/scene.h>

#include <cstdint>

namespace rad {

/// A point on a scene triangle, as a camera ray (or a probe) finds it.
struct SurfaceHit {
  Vec3 point{0.0f};
  Vec3 normal{0.0f};  ///< unit geometric normal of the triangle's front side
  uint32_t triangle = 0;
  bool frontFace = true;  ///< the viewer is on the front side
};

class SurfaceRadiance {
 public:
  virtual ~SurfaceRadiance() = default;
  /// Radiance (W / (m^2 sr), scene units) leaving the surface at `hit` toward the viewer;
  /// 0 from the back of a one-sided face. Safe to call from many threads at once.
  virtual Color radiance(const SurfaceHit& hit) const = 0;
};

struct SurfaceRenderSettings {
  int samplesPerPixel = 4;  ///< jittered camera rays per pixel (antialiasing)
  uint64_t seed = 1;
};

/// Renders what `camera` sees of `scene`, each visible point shaded by `radiance`.
/// Throws rad::Cancelled if `progress` returns false.
Image renderSurfaceRadiance(const Scene& scene, const Camera& camera, const SurfaceRadiance& radiance,
                            const SurfaceRenderSettings& settings, const ProgressCallback& progress = {});

}  // namespace rad
