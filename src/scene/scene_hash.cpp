#include "scene/scene_hash.h"

namespace rad {

void hashGeometry(Hasher& h, const Scene& scene) {
  h.value(uint64_t(scene.positions.size()));
  h.bytes(scene.positions.data(), scene.positions.size() * sizeof(Vec3));
  h.value(uint64_t(scene.triangles.size()));
  h.bytes(scene.triangles.data(), scene.triangles.size() * sizeof(UVec3));
  h.value(uint64_t(scene.faces.size()));
  for (const Face& f : scene.faces) {
    h.value(f.firstTriangle);
    h.value(f.triangleCount);
    const Material& m = scene.materials[f.material];
    h.value(uint8_t(m.twoSided));
    h.value(uint64_t(f.corners.size()));
    h.bytes(f.corners.data(), f.corners.size() * sizeof(uint32_t));
    // Coverage decides which rays pass: it is geometry to the form factors and the voxels.
    if (m.opaque()) continue;
    h.value(m.alphaMode);
    h.value(m.alpha);
    h.value(m.alphaCutoff);
    h.value(m.transmission);
    h.value(m.alphaTexture.texture ? m.alphaTexture.texture->digest() : uint64_t(0));
    h.bytes(m.alphaTexture.transform, sizeof m.alphaTexture.transform);
    h.value(m.alphaTexture.wrapU);
    h.value(m.alphaTexture.wrapV);
  }
  if (!scene.hasCoverage()) return;
  h.value(uint64_t(scene.texcoords.size()));
  h.bytes(scene.texcoords.data(), scene.texcoords.size() * sizeof(Vec2));
  h.value(uint64_t(scene.vertexAlpha.size()));
  h.bytes(scene.vertexAlpha.data(), scene.vertexAlpha.size() * sizeof(float));
}

void hashMaterials(Hasher& h, const Scene& scene) {
  for (const Face& f : scene.faces) {
    const Material& m = scene.materials[f.material];
    h.value(m.rho);
    h.value(m.emission);
    h.text(m.name);  // emitting materials name light groups
    for (const TextureMap* map : {&m.rhoTexture, &m.emissionTexture}) {
      h.value(map->texture ? map->texture->digest() : uint64_t(0));
      h.value(map->wrapU);
      h.value(map->wrapV);
      h.bytes(map->transform, sizeof map->transform);
    }
  }
  h.value(uint64_t(scene.texcoords.size()));
  h.bytes(scene.texcoords.data(), scene.texcoords.size() * sizeof(Vec2));
}

void hashLights(Hasher& h, std::span<const Light> lights) {
  h.value(uint64_t(lights.size()));
  for (const Light& l : lights) {
    h.value(l.type);
    h.value(l.position);
    h.value(l.direction);
    h.value(l.intensity);
    h.value(l.innerAngleDeg);
    h.value(l.outerAngleDeg);
    h.text(l.group);
    h.text(l.iesFile);
    h.value(l.lobes);
    if (l.type == LightType::Object) h.value(l.radius);  // made by the program, never in files
    if (l.type != LightType::Sky) continue;
    h.value(l.sky.model);
    h.value(l.sky.up);
    h.value(l.sky.towardSun);
    h.value(l.sky.forward);
    if (!l.sky.map) continue;
    h.value(l.sky.map->width);
    h.bytes(l.sky.map->pixels.data(), l.sky.map->pixels.size() * sizeof(Color));
  }
}

}  // namespace rad
