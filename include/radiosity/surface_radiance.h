#pragma once
// The one interface every radiosity method ends in: the outgoing radiance at a surface point.
// The renderer, the exporters and the probes only know this interface.

#include <radiosity/image.h>
#include <radiosity/progress.h>
#include <radiosity/ray_caster.h>
#include <radiosity/scene.h>

#include <cstdint>
#include <span>

namespace rad {

/// A point on a scene triangle, as a camera ray (or a probe) finds it.
struct SurfaceHit {
  Vec3 point{0.0f};
  Vec3 normal{0.0f};  ///< unit geometric normal of the triangle's front side
  uint32_t triangle = 0;
  bool frontFace = true;  ///< the viewer is on the front side
  /// Where on the triangle: point = (1-u-v) p0 + u p1 + v p2 (textures are looked up there).
  Vec2 barycentric{0.0f};
};

class SurfaceRadiance {
 public:
  virtual ~SurfaceRadiance() = default;
  /// Radiance (W / (sr scene unit^2)) leaving the surface at `hit` toward the viewer;
  /// 0 from the back of a one-sided face. Safe to call from many threads at once.
  virtual Color radiance(const SurfaceHit& hit) const = 0;
  /// True where indirectIrradiance() answers: the method kept its direct light apart.
  virtual bool hasIndirectIrradiance() const { return false; }
  /// The irradiance at `hit` of light that has bounced at least once: the solution's H less
  /// the direct light of lights and emitting surfaces, interpolated as radiance() interpolates
  /// H (0 where hasIndirectIrradiance() is false). A renderer adds the direct light per pixel.
  virtual Color indirectIrradiance(const SurfaceHit& /*hit*/) const { return Color(0.0f); }
  /// The point, spot and IES lights whose direct light indirectIrradiance() leaves out (those
  /// the solution was solved with), for the renderer to add per pixel.
  virtual std::span<const Light> directLights() const { return {}; }
  /// Per scene material, the factor on its emission that radiance() shows (its light group's
  /// scale, light_groups.h); empty: the scene's own emission. A renderer that adds the direct
  /// light per pixel applies it to the emitters it samples too.
  virtual std::span<const Color> emissionScales() const { return {}; }
};

/// Where a radiosity picture's direct light comes from.
enum class DirectLightMode {
  PerPixel,  ///< shadow rays at every camera ray's hit: hard shadows and beam edges stay sharp
  Solution,  ///< the solution's own H, interpolated over its patches or voxels
};

struct SurfaceRenderSettings {
  int samplesPerPixel = 4;  ///< jittered camera rays per pixel (antialiasing)
  uint64_t seed = 1;
  DirectLightMode direct = DirectLightMode::PerPixel;
  /// Per-pixel direct light: area samples of the emitting surfaces at each camera ray's hit
  /// (point, spot and IES lights take one shadow ray each).
  int emitterSamples = 8;
  /// Each pixel the irradiance arriving at its hit, on the side seen (W per square scene unit),
  /// not the radiance leaving it: a false-colour picture's (false_colour.h). Needs per-pixel
  /// direct light.
  bool irradiance = false;
};

/// Renders what `camera` sees of `scene`, each visible point shaded by `radiance`: with
/// DirectLightMode::PerPixel (where `radiance` has indirect irradiance) as Ke + rho (D + H_ind)
/// / pi, D the direct light by shadow rays at the hit; else as radiance() says.
/// Throws rad::Cancelled if `progress` returns false.
Image renderSurfaceRadiance(const Scene& scene, const Camera& camera,
                            const SurfaceRadiance& radiance, const SurfaceRenderSettings& settings,
                            const ProgressCallback& progress = {});
/// The same through `caster` (built over `scene`), shared with the run's other stages.
Image renderSurfaceRadiance(const Scene& scene, const RayCaster& caster, const Camera& camera,
                            const SurfaceRadiance& radiance, const SurfaceRenderSettings& settings,
                            const ProgressCallback& progress = {});

}  // namespace rad
