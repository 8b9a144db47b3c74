#include "lighting/emitter_sampler.h"

#include <radiosity/light_groups.h>

namespace rad {

EmitterSampler::EmitterSampler(const Scene& scene, std::span<const Color> emissionScales)
    : scene_(&scene),
      emissionScales_(emissionScales.begin(), emissionScales.end()),
      pdfArea_(scene.triangles.size(), 0.0f) {
  std::vector<double> weights;
  for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
    const Material& m = scene.materialOf(t);
    if (!m.emits()) continue;
    // pi is common to every weight; luminance is positive whenever any channel is.
    const Color emission = scaledEmission(scene, scene.faceOf(t).material, emissionScales_);
    const double weight = double(luminance(glm::max(emission, Color(0.0f)))) *
                          double(scene.triangleArea(t)) * (m.twoSided ? 2.0 : 1.0) *
                          double(scene.coverageMean(t));
    if (!(weight > 0.0)) continue;
    triangles_.push_back(t);
    weights.push_back(weight);
  }
  if (triangles_.empty()) return;
  distribution_ = DiscreteDistribution(weights);
  for (size_t i = 0; i < triangles_.size(); ++i) {
    const uint32_t t = triangles_[i];
    pdfArea_[t] = float(distribution_.pmf(i) / double(scene.triangleArea(t)));
  }
}

EmitterSample EmitterSampler::sample(float choose, Vec2 position) const {
  const size_t i = distribution_.sample(choose);
  const uint32_t t = triangles_[i];
  const UVec3& tri = scene_->triangles[t];
  const Vec2 b = sampleUniformTriangle(position);
  const Material& m = scene_->materialOf(t);
  EmitterSample s;
  s.point = (1.0f - b.x - b.y) * scene_->positions[tri.x] + b.x * scene_->positions[tri.y] +
            b.y * scene_->positions[tri.z];
  s.normal = scene_->triangleNormal(t);
  s.emission = scaledEmission(*scene_, scene_->faceOf(t).material, emissionScales_) *
               scene_->textureAt(m.emissionTexture, t, b) * scene_->coverageAt(t, b);
  s.twoSided = m.twoSided;
  s.pdfArea = pdfArea_[t];
  return s;
}

}  // namespace rad
