#include "lit_mesh/lit_mesh_texturing.h"

namespace rad {

LitMeshTexturing::LitMeshTexturing(const Scene& scene, LitMesh& mesh)
    : scene_(scene), mesh_(mesh), textureOfMaterial_(scene.materials.size(), LitMesh::kUntextured) {
  for (uint32_t m = 0; m < scene.materials.size(); ++m) any_ = any_ || textured(m);
}

bool LitMeshTexturing::textured(uint32_t material) const {
  const Material& m = scene_.materials[material];
  return m.rhoTexture && !m.emits() && !scene_.texcoords.empty();
}

uint32_t LitMeshTexturing::textureOf(uint32_t material) {
  uint32_t& index = textureOfMaterial_[material];
  if (index != LitMesh::kUntextured) return index;
  const Material& m = scene_.materials[material];
  mesh_.textures.push_back(
      {m.name, m.rhoTexture.texture, m.rhoTexture.wrapU, m.rhoTexture.wrapV, m.rho});
  return index = uint32_t(mesh_.textures.size() - 1);
}

Vec2 LitMeshTexturing::texcoordAt(uint32_t triangle, Vec2 b) const {
  return scene_.materialOf(triangle).rhoTexture.apply(scene_.texcoordAt(triangle, b));
}

Vec2 LitMeshTexturing::texcoordOnFace(uint32_t face, const Vec3& point) const {
  uint32_t triangle = 0;
  const Vec2 b = scene_.locateOnFace(face, point, triangle);
  return texcoordAt(triangle, b);
}

void LitMeshTexturing::addTriangle(uint32_t material) {
  if (!any_) return;
  mesh_.triangleTextures.push_back(textured(material) ? textureOf(material) : LitMesh::kUntextured);
}

void LitMeshTexturing::addVertex(Vec2 texcoord) {
  if (any_) mesh_.texcoords.push_back(texcoord);
}

}  // namespace rad
