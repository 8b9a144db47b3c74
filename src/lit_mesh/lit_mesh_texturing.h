#pragma once
// Which materials a lit mesh shows through their textures, shared by the methods' exports: a
// textured vertex carries irradiance / pi, which the texture times its factor multiplies in the
// viewer (glTF's COLOR_0 times the base colour), so the texture's detail survives the bake.

#include <radiosity/scene.h>
#include <radiosity/surface_solution.h>

#include <vector>

namespace rad {

class LitMeshTexturing {
 public:
  /// Fills mesh.textures as materials are asked for; the mesh must outlive this.
  LitMeshTexturing(const Scene& scene, LitMesh& mesh);
  /// True when some material's faces go out textured.
  bool any() const { return any_; }
  /// True when `material`'s faces go out textured: a base colour texture, coordinates in the
  /// scene, and no emission (which the texture must not multiply).
  bool textured(uint32_t material) const;
  /// The texture index in mesh.textures of a textured material (made on first use).
  uint32_t textureOf(uint32_t material);
  /// Texture coordinates at a point of a face (the material's transform applied).
  Vec2 texcoordOnFace(uint32_t face, const Vec3& point) const;
  /// The same at barycentric `b` of a triangle.
  Vec2 texcoordAt(uint32_t triangle, Vec2 b) const;
  /// Appends a triangle's texture (kUntextured for an untextured material), keeping
  /// mesh.triangleTextures one per triangle once any is textured.
  void addTriangle(uint32_t material);
  /// Keeps mesh.texcoords one per vertex once any vertex has them; (0, 0) for untextured ones.
  void addVertex(Vec2 texcoord = Vec2(0.0f));

 private:
  const Scene& scene_;
  LitMesh& mesh_;
  std::vector<uint32_t> textureOfMaterial_;
  bool any_ = false;
};

}  // namespace rad
