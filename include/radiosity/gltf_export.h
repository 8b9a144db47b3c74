#pragma once
// A lit triangle mesh written as binary glTF 2.0 (.glb): per-vertex linear colours (the baked
// outgoing radiance) under a white KHR_materials_unlit material, so that any glTF viewer or
// Blender shows the solved lighting as it is, without relighting it. The description is neutral
// (no patches or voxels) so that every radiosity method can export through it.

#include <radiosity/image.h>
#include <radiosity/surface_solution.h>

#include <cstdint>
#include <string>
#include <vector>

namespace rad {

/// A lightmap atlas a .glb shows in place of vertex colours: the mesh's lightmapTexcoords are
/// its TEXCOORD_1 (and its TEXCOORD_0 where the mesh has no texcoords of its own, since glTF's
/// sets must start at 0).
struct GlbLightmap {
  /// The light shown: the outgoing radiance per texel, linear (embedded as an sRGB PNG times
  /// 2^exposureEV, under an unlit material on TEXCOORD_1, so that any viewer shows it).
  Image radiance;
  /// The HDR irradiance atlas beside the file (EXR, relative to it), named in the asset's
  /// extras for engines: glTF images are PNG or JPEG only.
  std::string irradianceUri;
  float texelsPerUnit = 0.0f;
};

/// Writes `mesh` to `path` as a .glb, atomically (a temporary file renamed over `path`). Each
/// group becomes a node with its own mesh (vertices re-indexed per group; groups without
/// triangles are left out). Throws std::invalid_argument for an inconsistent description and
/// std::runtime_error naming `path` if the file cannot be written.
/// The colours are the mesh's times 2^exposureEV (then clamped to [0, 1]: glTF's COLOR_0), and the
/// asset's extras record it ({"radiosity": {"exposure_ev": ...}}).
/// With a `lightmap`, every triangle shows it instead (no COLOR_0).
void writeLitMeshGlb(const std::string& path, const LitMesh& mesh, float exposureEV = 0.0f,
                     const GlbLightmap* lightmap = nullptr);
/// The .glb's bytes, as writeLitMeshGlb writes them. Throws as it does.
std::string litMeshGlb(const LitMesh& mesh, float exposureEV = 0.0f,
                       const GlbLightmap* lightmap = nullptr);
/// The mesh's vertex indices in the order the .glb holds its vertices, node after node (a vertex
/// two groups share is in both): what a viewer's per-vertex arrays follow.
std::vector<uint32_t> glbVertexOrder(const LitMesh& mesh);

}  // namespace rad
