#pragma once
// Chooses a point on the scene's emissive triangles for next-event estimation: a triangle with
// probability proportional to its emitted power (luminance of pi * Ke * area * mean coverage,
// both sides of a two-sided one), then a point uniform in its area; what the point sends is
// its coverage there times Ke (Material: a surface that is not opaque emits c E a unit area). A
// light group's scale on a material's emission (light_groups.h) scales what it is chosen by and
// what it sends alike.

#include <radiosity/scene.h>

#include <span>
#include <vector>

#include "geometry/sampling.h"

namespace rad {

struct EmitterSample {
  Vec3 point{0.0f};
  Vec3 normal{0.0f};  ///< front normal of the chosen triangle
  Color emission{0.0f};
  bool twoSided = false;
  float pdfArea = 0.0f;  ///< density of `point` per unit area (choice probability / area)
};

class EmitterSampler {
 public:
  /// Keeps a pointer to `scene`, which must outlive the sampler. `emissionScales`: a factor on
  /// each material's emission (empty: none; materials past its end: 1; a material scaled to 0
  /// is never chosen).
  explicit EmitterSampler(const Scene& scene, std::span<const Color> emissionScales = {});

  bool empty() const { return triangles_.empty(); }
  /// `choose` picks the triangle, `position` the point in it; all uniform in [0, 1).
  EmitterSample sample(float choose, Vec2 position) const;
  /// Area density with which sample() returns points of `triangle` (0 for non-emitters).
  float pdfArea(uint32_t triangle) const { return pdfArea_[triangle]; }

 private:
  const Scene* scene_;
  std::vector<Color> emissionScales_;
  std::vector<uint32_t> triangles_;
  DiscreteDistribution distribution_;
  std::vector<float> pdfArea_;  // per scene triangle
};

}  // namespace rad
