#pragma once
// A lit triangle mesh written as binary glTF 2.0 (.glb): per-vertex linear colours (the baked
// outgoing radiance) under a white KHR_materials_unlit material, so that any glTF viewer or
// Blender shows the solved lighting as it is, without relighting it. The description is neutral
// (no patches or voxels) so that every radiosity method can export through it.

#include <radiosity/surface_solution.h>

#include <cstdint>
#include <string>
#include <vector>

namespace rad {

/// Writes `mesh` to `path` as a .glb, atomically (a temporary file renamed over `path`). Each
/// group becomes a node with its own mesh (vertices re-indexed per group; groups without
/// triangles are left out). Throws std::invalid_argument for an inconsistent description and
/// std::runtime_error naming `path` if the file cannot be written.
/// The colours are the mesh's times 2^exposureEV (then clamped to [0, 1]: glTF's COLOR_0), and the
/// asset's extras record it ({"radiosity": {"exposure_ev": ...}}).
void writeLitMeshGlb(const std::string& path, const LitMesh& mesh, float exposureEV = 0.0f);
/// The .glb's bytes, as writeLitMeshGlb writes them. Throws as it does.
std::string litMeshGlb(const LitMesh& mesh, float exposureEV = 0.0f);
/// The mesh's vertex indices in the order the .glb holds its vertices, node after node (a vertex
/// two groups share is in both): what a viewer's per-vertex arrays follow.
std::vector<uint32_t> glbVertexOrder(const LitMesh& mesh);

}  // namespace rad
