#pragma once
// Direct light at surface points: the one place that knows its physics. The path tracer's
// next-event estimation, the voxel method's first shot, the patch method's light injection and
// the per-pixel direct light of radiosity pictures all ask it, so the methods agree by
// construction. Analytic lights (point, spot, IES) are exact and noiseless: one shadow ray each.
// Emissive triangles are estimated by one area sample per call, chosen by emitted power. A sky
// (LightType::Sky) by stratified cosine-weighted rays that leave the scene, each bringing the
// sky's radiance from its direction.
// Units (docs/ARCHITECTURE.md): irradiance in W per square scene unit, intensity in W/sr.

#include <radiosity/ray_caster.h>
#include <radiosity/scene.h>

#include <span>

#include "core/rng.h"
#include "lighting/emitter_sampler.h"

namespace rad {

/// Rays with which fromLight estimates a sky at a point, and skyOver over a patch's points
/// together: at a floor point 2 units below a 1 x 1 roof opening (docs/references.md 5.5) they
/// leave 1.2% rms of its light (256 rays: 7.6%).
constexpr int kDefaultSkySamples = 4096;

class DirectLighting {
 public:
  /// Keeps pointers to `scene`, `caster` and `lights` (the scene's own by default), which must
  /// outlive it. Safe to use from many threads at once.
  DirectLighting(const Scene& scene, const RayCaster& caster);
  DirectLighting(const Scene& scene, const RayCaster& caster, std::span<const Light> lights);
  /// The same with a factor on each material's emission (a light group's scale, or 0 and 1 to
  /// take one group's emitters alone; empty: none) and the rays fromLight gives a sky.
  DirectLighting(const Scene& scene, const RayCaster& caster, std::span<const Light> lights,
                 std::span<const Color> emissionScales, int skySamples = kDefaultSkySamples);

  /// The analytic lights it evaluates.
  std::span<const Light> lights() const { return lights_; }
  bool hasLights() const { return !lights_.empty(); }
  bool hasEmitters() const { return !emitters_.empty(); }
  bool hasSky() const { return hasSky_; }

  /// Irradiance at `p` on a surface with unit front normal `n` from the scene's analytic lights,
  /// each seen through one shadow ray: sum of I(-w) cos(theta) / d^2 over the lights `p` sees
  /// (E cos(theta) for a directional light, whose shadow ray leaves the scene); a sky by
  /// `skySamples` rays (skyOver the one point).
  Color fromLights(const Vec3& p, const Vec3& n) const;
  /// The same from one light.
  Color fromLight(const Light& light, const Vec3& p, const Vec3& n) const;
  /// Irradiance at `p` (unit front normal `n`) from the skies among the lights: pi times the
  /// mean of the radiance that `samples` cosine-weighted rays (stratifiedSample's strata of the
  /// disk they lift from) bring from the sky where they leave the scene. Draws 2 numbers
  /// a ray from `rng`.
  Color fromSky(const Vec3& p, const Vec3& n, Rng& rng, int samples) const;
  /// The weighted mean (`weights` summing to 1) of the irradiance from sky `sky` at `points` of
  /// a plane of unit front normal `n`, by `skySamples` rays in all (an equal number a point),
  /// stratified together: a random permutation deals the points the strata of one
  /// stratifiedSample set, which keeps it unbiased and stratifies the whole (16 points 0.05 apart
  /// under the roof opening of docs/references.md 5.5, 4,096 rays: their mean within 2.0% rms,
  /// 2.4% as 16 sets of 256). The rays' stream is fixed by the first point and `n`: the same
  /// points get the same value.
  Color skyOver(const Light& sky, std::span<const Vec3> points, std::span<const double> weights,
                const Vec3& n) const;
  /// One ray from `p` toward sky `sky` for the point `u` of [0,1)^2 (mapped to the cosine
  /// hemisphere about n): pi times that ray's radiance from the sky, or nothing.
  Color skySample(const Light& sky, const Vec3& p, const Vec3& n, Vec2 u) const;
  /// The radiance the skies among the lights send along -w (skyRadiance below).
  Color skyRadiance(const Vec3& w) const;
  /// One-sample estimate of the irradiance from emissive triangles (draws two numbers from
  /// `rng`). With `misWeighted`, the sample carries its power-heuristic weight against a
  /// cosine-weighted bounce, which then adds the emission it hits (see emitterPdfArea).
  Color sampleEmitters(const Vec3& p, const Vec3& n, Rng& rng, bool misWeighted = false) const;
  /// Area density with which sampleEmitters picks points of `triangle` (0 for non-emitters).
  float emitterPdfArea(uint32_t triangle) const { return emitters_.pdfArea(triangle); }

  /// Distance to lift a ray's origin off the surface at `p`, grown with the coordinates'
  /// magnitude (floats near magnitude m are good to about 6e-8 m).
  float rayOffset(const Vec3& p) const;
  /// True if nothing lies between `p` (lifted along `n`) and `target`, or and the sphere of
  /// radius `stopShort` around it (an object light's own surface).
  bool visible(const Vec3& p, const Vec3& n, const Vec3& target, float stopShort = 0.0f) const;
  /// True if nothing lies along the unit direction `w` from `p` (lifted along `n`): it sees out
  /// of the scene.
  bool visibleToward(const Vec3& p, const Vec3& n, const Vec3& w) const;

 private:
  const RayCaster* caster_;
  std::span<const Light> lights_;
  EmitterSampler emitters_;
  float sceneExtent_;
  int skySamples_;
  bool hasSky_ = false;
};

/// The radiance the skies among `lights` send along -w: what a ray along the unit direction w
/// that left the scene sees.
Color skyRadiance(std::span<const Light> lights, const Vec3& w);

/// The power heuristic with exponent 2 (Veach and Guibas 1995): the weight of a sample taken
/// with density `pdf` against another technique's `otherPdf`.
inline float powerHeuristic(float pdf, float otherPdf) {
  const float a = pdf * pdf, b = otherPdf * otherPdf;
  return a > 0.0f ? a / (a + b) : 0.0f;
}

}  // namespace rad
