#pragma once
// A solution's light baked into the scene's own triangles: each triangle is cut into smaller
// ones, fine enough to follow the solution (no edge longer than `maxEdge`), and every vertex
// takes the radiance the renderer shows there. Works for any SurfaceRadiance; the
// voxel method uses it for its .glb export (the patch method exports its own patch mesh).

#include <radiosity/scene.h>
#include <radiosity/surface_radiance.h>
#include <radiosity/surface_solution.h>

namespace rad {

/// The scene's triangles, one group per scene object, each cut (longest-edge bisection, slivers
/// into strips) until no edge is longer than maxEdge, vertex colours the linear radiance leaving
/// the front. A two-sided material's back side comes as pieces of its own (wound the other way,
/// coloured with the back's radiance), so every triangle is one-sided: a wall lit on one side
/// stays dark on the other. Evaluates `radiance` in parallel. Throws std::invalid_argument,
/// before any work, when the cut would exceed kMaxBakedTriangles.
LitMesh bakeSurfaceRadiance(const Scene& scene, const SurfaceRadiance& radiance, float maxEdge);
/// The same for an export: the faces of textured materials under their textures (texture
/// coordinates, LitMesh::textures), their vertices coloured with the solution's irradiance / pi
/// (LitMeshTexturing).
LitMesh bakeSurfaceLight(const Scene& scene, const SurfaceSolution& solution, float maxEdge);

/// A bake in two steps: the cut triangles and where each vertex lies, then their colours, so
/// that a viewer shades the same vertices again as the light changes.
struct SurfaceBake {
  LitMesh mesh;                ///< colours black until shaded
  std::vector<SurfaceHit> at;  ///< per vertex: the point radiance() is asked at
  /// Per vertex, it lies under a texture (a cut with textures); empty: none does.
  std::vector<uint8_t> underTexture;
};
/// The cut of bakeSurfaceRadiance, unshaded; `withTextures`: the textured materials' faces
/// under their textures (bakeSurfaceLight's). Throws as it does.
SurfaceBake cutSurfaces(const Scene& scene, float maxEdge, bool withTextures = false);
/// Sets every vertex colour to the radiance `radiance` gives there (in parallel).
void shadeSurfaces(SurfaceBake& bake, const SurfaceRadiance& radiance);

/// The most triangles a bake may make (about 1 GB of glTF).
inline constexpr double kMaxBakedTriangles = 3e7;

}  // namespace rad
