#pragma once
// Builds a Scene from polygons: triangulates them, remembers each planar face, drops degenerate
// triangles (one warning that counts them) and rejects non-finite coordinates. Every loader and
// built-in scene goes through it, so all of them obey the same rules.

#include <radiosity/scene.h>

#include <array>
#include <optional>
#include <span>
#include <string>

namespace rad {

/// Largest coordinate a scene may have, in scene units. Rays are cast in 32-bit floats, whose
/// spacing at 1e9 is 64 units: beyond that a scene is not resolvable (and Embree asserts on
/// origins near 1e18). A kilometre-wide site in millimetres is 1e6.
constexpr float kMaxSceneCoordinate = 1e9f;

/// Largest light a scene, a request or a light group's scale may set: a light's intensity (W/sr)
/// and a material's emission (W/(sr unit^2)), the scaled ones included. Beyond any lamp or sun in
/// any length unit (the sun's intensity is 3e25 W/sr, but seen from 1 AU as 1.4e3 W/m^2 of
/// irradiance), and 20 orders of magnitude below a float's range, so that no product a solve
/// forms (over areas, form factors, bounces) overflows to infinity or NaN.
constexpr float kMaxLight = 1e18f;

/// The reflectance a file's 1 becomes: the solvers need rho below 1.
constexpr float kMaxReflectance = 0.999f;

class SceneBuilder {
 public:
  explicit SceneBuilder(std::string sceneName);

  /// Adds a material; a reflectance of 1 (a factor of 1, a white texture) is taken as
  /// kMaxReflectance, counted in one warning of build(). Throws InputError naming the material if a
  /// component of rho or emission is not finite, or rho, alpha, the alpha cutoff or transmission is
  /// outside [0, 1].
  uint32_t addMaterial(Material material);
  uint32_t addObject(std::string name);
  /// Adds a vertex; `where` names the source (file:line) for the error if it is NaN, infinite or
  /// beyond kMaxSceneCoordinate.
  uint32_t addVertex(const Vec3& position, const std::string& where);
  /// The same with texture coordinates (u across, v down from the image's top; non-finite
  /// ones are an InputError naming `where`).
  uint32_t addVertex(const Vec3& position, const Vec2& texcoord, const std::string& where);
  /// Gives an added vertex texture coordinates (a generator mapping its faces after making
  /// them). Throws InputError naming `where` when they are not finite.
  void setTexcoord(uint32_t vertex, const Vec2& texcoord, const std::string& where);
  /// Gives an added vertex its colour's alpha (glTF COLOR_0); the others keep 1. Throws
  /// InputError naming `where` when it is not in [0, 1].
  void setVertexAlpha(uint32_t vertex, float alpha, const std::string& where);
  /// Adds a polygon given by vertex indices, counter-clockwise about its front side.
  /// A planar polygon becomes one Face (triangulated by ear clipping, so concave ones work);
  /// a non-planar one becomes a face per triangle. Throws InputError (naming `where`) for fewer
  /// than 3 corners or an index out of range.
  void addPolygon(std::span<const uint32_t> corners, uint32_t material, uint32_t object,
                  const std::string& where);
  /// Adds an indexed triangle list (glTF). Adjacent coplanar triangles with the same material
  /// that form a convex quad are remembered as one face, the rest as a face each.
  void addTriangleMesh(std::span<const uint32_t> indices, uint32_t material, uint32_t object,
                       const std::string& where);

  Scene& scene() { return scene_; }
  /// Records a warning about the input `file`. Warnings are shown after the scene's name, so the
  /// file is named only when it is not the scene's own (a mesh a JSON scene includes).
  void warn(const std::string& file, const std::string& text);
  /// Finishes the scene: records the degenerate-triangle warning, makes the first of the files'
  /// cameras the scene's when it has none, gives a textured material whose faces lack texture
  /// coordinates its texture's mean (one warning naming them), and returns it.
  Scene build();

 private:
  void addFace(std::span<const uint32_t> corners, std::span<const UVec3> triangles,
               uint32_t material, uint32_t object);
  bool isDegenerate(const UVec3& triangle) const;
  void resolveUnmappedTextures();
  /// The convex planar quad two triangles form when they share a diagonal, if they do.
  std::optional<std::array<uint32_t, 4>> quadOf(const UVec3& a, const UVec3& b) const;

  Scene scene_;
  size_t degenerateTriangles_ = 0;
  size_t clampedMaterials_ = 0;       ///< materials whose reflectance of 1 became kMaxReflectance
  std::vector<uint8_t> hasTexcoord_;  ///< per vertex, once a vertex has had coordinates
};

}  // namespace rad
