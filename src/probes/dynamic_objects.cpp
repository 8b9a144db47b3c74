// Probes and vertex irradiance for the dynamic objects placed in a scene.
#include "probes/dynamic_objects.h"

#include <tbb/parallel_for.h>

#include <glm/gtc/constants.hpp>

#include "lighting/direct_lighting.h"

namespace rad {

ProbeCache::ProbeCache() : state_(std::make_unique<State>()) {}
ProbeCache::~ProbeCache() = default;
void ProbeCache::invalidate() {
  state_->probes.clear();
}
size_t ProbeCache::captures() const {
  return state_->captures;
}

namespace {

// What the static surfaces reflect: the solution's radiance less what they emit.
class ReflectedOnly : public SurfaceRadiance {
 public:
  ReflectedOnly(const Scene& scene, const SurfaceSolution& solution)
      : scene_(scene), solution_(solution), scales_(solution.emissionScales()) {}
  Color radiance(const SurfaceHit& hit) const override {
    const Color l = solution_.radiance(hit);
    if (!hit.frontFace) return l;
    const Color ke = scaledEmission(scene_, scene_.faceOf(hit.triangle).material, scales_);
    return glm::max(l - ke, Color(0.0f));
  }

 private:
  const Scene& scene_;
  const SurfaceSolution& solution_;
  std::span<const Color> scales_;
};

// Each object's vertices (of the placed scene), and their area-weighted normals.
struct ObjectVertices {
  std::vector<std::vector<uint32_t>> byObject;
  std::vector<Vec3> normals;
};
ObjectVertices objectVertices(const Scene& placed) {
  ObjectVertices out;
  out.byObject.resize(placed.objects.size());
  out.normals.assign(placed.positions.size(), Vec3(0.0f));
  std::vector<uint8_t> seen(placed.positions.size(), 0);
  for (uint32_t t = placed.staticTriangles; t < placed.triangles.size(); ++t) {
    const UVec3& tri = placed.triangles[t];
    const Vec3 weighted = placed.triangleNormal(t) * placed.triangleArea(t);
    for (int k = 0; k < 3; ++k) {
      out.normals[tri[k]] += weighted;
      if (!seen[tri[k]]) {
        seen[tri[k]] = 1;
        out.byObject[placed.faceOf(t).object].push_back(tri[k]);
      }
    }
  }
  for (Vec3& n : out.normals)
    if (glm::length(n) > 0.0f) n = glm::normalize(n);
  return out;
}

}  // namespace

DynamicObjectLighting::DynamicObjectLighting(const Scene& placed, const SurfaceSolution& solution,
                                             const RayCaster& staticCaster,
                                             const RayCaster& placedCaster,
                                             const DynamicObjectSettings& settings,
                                             ProbeCache* cache)
    : placed_(placed),
      solution_(solution),
      full_(placed.positions.size(), Color(0.0f)),
      indirect_(placed.positions.size(), Color(0.0f)) {
  const ObjectVertices vertices = objectVertices(placed);
  centres_.assign(placed.objects.size(), Vec3(0.0f));
  radii_.assign(placed.objects.size(), 0.0f);
  for (const Light& light : solution.directLights())
    (light.type == LightType::Object ? objectLights_ : pointLights_).push_back(light);
  fromObjects_ = std::make_unique<DirectLighting>(solution.scene(), staticCaster, objectLights_);
  const ReflectedOnly reflected(solution.scene(), solution);
  const DirectLighting direct(placed, placedCaster, pointLights_, solution.emissionScales());
  for (size_t object = 0; object < vertices.byObject.size(); ++object) {
    const std::vector<uint32_t>& own = vertices.byObject[object];
    if (own.empty()) continue;
    Vec3 centre(0.0f);
    Bounds box;
    for (uint32_t v : own) {
      centre += placed.positions[v] / float(own.size());
      box.extend(placed.positions[v]);
    }
    centres_[object] = centre;
    for (uint32_t v : own)
      radii_[object] = std::max(radii_[object], glm::distance(placed.positions[v], centre));
    // One probe at the centre, or for a large object a grid over its box (at most
    // probeSpacing apart), each vertex blending them by inverse squared distance.
    std::vector<Vec3> at = {centre};
    if (settings.probeSpacing > 0.0f) {
      const Vec3 size = box.max - box.min;
      const glm::ivec3 n = glm::max(glm::ivec3(glm::ceil(size / settings.probeSpacing)), 1);
      if (n.x * n.y * n.z > 1) {
        at.clear();
        for (int k = 0; k < n.z; ++k)
          for (int j = 0; j < n.y; ++j)
            for (int i = 0; i < n.x; ++i)
              at.push_back(box.min + size * (Vec3(i, j, k) + 0.5f) / Vec3(n));
      }
    }
    std::vector<const ProbeCache::State::Probes*> probes;
    std::vector<ProbeCache::State::Probes> uncached(at.size());
    for (size_t k = 0; k < at.size(); ++k) {
      const std::string key = placed.objects[object].name + "#" + std::to_string(k);
      ProbeCache::State::Probes& p = cache ? cache->state().probes[key] : uncached[k];
      if (!p.full || glm::length(at[k] - p.centre) > settings.probeMoveThreshold) {
        auto full = std::make_shared<CubeProbe>(settings.probeResolution);
        auto bounce = std::make_shared<CubeProbe>(settings.probeResolution);
        full->capture(staticCaster, solution, at[k]);
        bounce->capture(staticCaster, reflected, at[k]);
        p = {at[k], std::move(full), std::move(bounce)};
        if (cache) ++cache->state().captures;
      }
      probes.push_back(&p);
    }
    tbb::parallel_for(size_t(0), own.size(), [&](size_t k) {
      const uint32_t v = own[k];
      const Vec3& n = vertices.normals[v];
      const Vec3 p = placed.positions[v];
      Color full(0.0f), bounce(0.0f);
      float total = 0.0f;
      for (const ProbeCache::State::Probes* probe : probes) {
        const Vec3 d = p - probe->centre;
        const float w = probes.size() == 1 ? 1.0f : 1.0f / (glm::dot(d, d) + 1e-12f);
        full += w * probe->full->irradiance(n, settings.way);
        bounce += w * probe->bounce->irradiance(n, settings.way);
        total += w;
      }
      full_[v] = full / total + direct.fromLights(p, n);
      indirect_[v] = bounce / total;
    });
  }
}

std::vector<DynamicObjectLighting::ObjectLobes> DynamicObjectLighting::objectLobes() const {
  std::vector<ObjectLobes> out(placed_.objects.size());
  std::vector<std::array<Vec3d, 6>> weighted(placed_.objects.size());
  std::vector<std::array<double, 6>> weights(placed_.objects.size());
  for (uint32_t t = placed_.staticTriangles; t < placed_.triangles.size(); ++t) {
    const UVec3& tri = placed_.triangles[t];
    const Color rho =
        placed_.reflectanceAt(t, Vec2(1.0f / 3.0f), std::sqrt(placed_.triangleArea(t)));
    const Color b = rho * (full_[tri.x] + full_[tri.y] + full_[tri.z]) / 3.0f;
    const Vec3 n = placed_.triangleNormal(t);
    const float weight = placed_.triangleArea(t) / glm::pi<float>();
    const Vec3 centroid =
        (placed_.positions[tri.x] + placed_.positions[tri.y] + placed_.positions[tri.z]) / 3.0f;
    const uint32_t object = placed_.faceOf(t).object;
    out[object].present = true;
    for (size_t k = 0; k < 6; ++k) {
      const Color lobe = b * (weight * axisLobe(n, int(k)));
      out[object].lobes[k] += lobe;
      // Where the lobe's light leaves from: its triangles' centroids, weighted by their share.
      const double w = luminance(lobe);
      weighted[object][k] += w * Vec3d(centroid);
      weights[object][k] += w;
    }
  }
  for (size_t o = 0; o < out.size(); ++o)
    for (size_t k = 0; k < 6; ++k)
      out[o].origins[k] = weights[o][k] > 0.0 ? Vec3(weighted[o][k] / weights[o][k]) : centres_[o];
  return out;
}

std::vector<Light> DynamicObjectLighting::objectLights() const {
  const std::vector<ObjectLobes> lobes = objectLobes();
  std::vector<Light> lights;
  for (size_t o = 0; o < lobes.size(); ++o) {
    if (!lobes[o].present) continue;
    // A light per lobe, from where the surface facing its way lies (not from the centre: a
    // wall 0.45 from a 0.3 m cube's face got 12% too little of its light from 0.6). Six each,
    // dark ones too, so that a relighter matches them frame to frame.
    for (size_t k = 0; k < 6; ++k) {
      Light light;
      light.type = LightType::Object;
      light.position = lobes[o].origins[k];
      light.lobes[k] = lobes[o].lobes[k];
      light.radius = radii_[o] + glm::distance(light.position, centres_[o]);
      light.intensity = Color(1.0f);
      light.group = "object:" + placed_.objects[o].name;
      lights.push_back(light);
    }
  }
  return lights;
}

void DynamicObjectLighting::appendObjects(LitMesh& mesh) const {
  for (uint32_t t = placed_.staticTriangles; t < placed_.triangles.size();) {
    const uint32_t object = placed_.faceOf(t).object;
    const uint32_t first = uint32_t(mesh.indices.size() / 3);
    for (; t < placed_.triangles.size() && placed_.faceOf(t).object == object; ++t) {
      const Vec3 n = placed_.triangleNormal(t);
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = placed_.triangles[t][k];
        mesh.indices.push_back(uint32_t(mesh.positions.size()));
        mesh.positions.push_back(placed_.positions[v]);
        mesh.normals.push_back(n);
        const Vec2 corner(k == 1 ? 1.0f : 0.0f, k == 2 ? 1.0f : 0.0f);
        mesh.colors.push_back(placed_.reflectanceAt(t, corner) * full_[v] / glm::pi<float>());
      }
    }
    mesh.groups.push_back(
        {placed_.objects[object].name, first, uint32_t(mesh.indices.size() / 3) - first});
  }
  // The objects show their colours, untextured, in a mesh whose static faces may be textured.
  if (!mesh.texcoords.empty()) mesh.texcoords.resize(mesh.positions.size(), Vec2(0.0f));
  if (!mesh.triangleTextures.empty())
    mesh.triangleTextures.resize(mesh.indices.size() / 3, LitMesh::kUntextured);
}

std::vector<DynamicObjectSummary> DynamicObjectLighting::summaries() const {
  std::vector<Vec3d> sum(placed_.objects.size(), Vec3d(0.0));
  std::vector<double> area(placed_.objects.size(), 0.0);
  for (uint32_t t = placed_.staticTriangles; t < placed_.triangles.size(); ++t) {
    const UVec3& tri = placed_.triangles[t];
    const uint32_t object = placed_.faceOf(t).object;
    const double a = placed_.triangleArea(t);
    sum[object] += a * Vec3d(full_[tri.x] + full_[tri.y] + full_[tri.z]) / 3.0;
    area[object] += a;
  }
  std::vector<DynamicObjectSummary> out;
  const std::vector<ObjectLobes> lobes = objectLobes();
  for (size_t o = 0; o < sum.size(); ++o) {
    if (!(area[o] > 0.0)) continue;
    out.push_back({placed_.objects[o].name, Color(sum[o] / area[o]), lobes[o].lobes});
  }
  return out;
}

Color DynamicObjectLighting::atHit(const SurfaceHit& hit,
                                   const std::vector<Color>& perVertex) const {
  const UVec3& t = placed_.triangles[hit.triangle];
  const Vec3 a = placed_.positions[t.x], b = placed_.positions[t.y], c = placed_.positions[t.z];
  const Vec3 e1 = b - a, e2 = c - a, d = hit.point - a;
  const float d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
  const float d1 = glm::dot(d, e1), d2 = glm::dot(d, e2);
  const float det = d11 * d22 - d12 * d12;
  if (!(det > 0.0f)) return (perVertex[t.x] + perVertex[t.y] + perVertex[t.z]) / 3.0f;
  const float v = glm::clamp((d22 * d1 - d12 * d2) / det, 0.0f, 1.0f);
  const float w = glm::clamp((d11 * d2 - d12 * d1) / det, 0.0f, 1.0f - v);
  return (1.0f - v - w) * perVertex[t.x] + v * perVertex[t.y] + w * perVertex[t.z];
}

Color DynamicObjectLighting::radiance(const SurfaceHit& hit) const {
  if (!isObject(hit.triangle)) return solution_.radiance(hit);
  const Material& m = placed_.materialOf(hit.triangle);
  if (!hit.frontFace && !m.twoSided) return Color(0.0f);
  return placed_.reflectanceAt(hit.triangle, hit.barycentric) * atHit(hit, full_) /
         glm::pi<float>();
}

Color DynamicObjectLighting::indirectIrradiance(const SurfaceHit& hit) const {
  if (!isObject(hit.triangle)) {
    const Color bounce = solution_.indirectIrradiance(hit);
    if (objectLights_.empty()) return bounce;
    const Vec3 n = hit.frontFace ? hit.normal : -hit.normal;
    return bounce + fromObjects_->fromLights(hit.point, n);
  }
  const Material& m = placed_.materialOf(hit.triangle);
  if (!hit.frontFace && !m.twoSided) return Color(0.0f);
  return atHit(hit, indirect_);
}

}  // namespace rad
