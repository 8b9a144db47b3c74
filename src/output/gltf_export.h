#pragma once
// A lit triangle mesh written as binary glTF 2.0 (.glb): per-vertex linear colours (the baked
// outgoing radiance) under a white KHR_materials_unlit material, so that any glTF viewer or
// Blender shows the solved lighting as it is, without relighting it. The description is neutral
// (no patches or voxels) so that every radiosity method can export through it.

#include <radiosity/types.h>

#include <cstdint>
#include <string>
#include <vector>

namespace rad {

/// A run of triangles written as one glTF node (and mesh), named e.g. after a scene object.
struct LitMeshGroup {
  std::string name;
  uint32_t firstTriangle = 0;
  uint32_t triangleCount = 0;
};

struct LitMesh {
  std::vector<Vec3> positions;  ///< scene units
  std::vector<Vec3> normals;    ///< per vertex; normalised on write
  std::vector<Color> colors;    ///< linear RGB per vertex; clamped to [0, 1] on write
  /// 3 per triangle, CCW about the side it shows (one-sided: a surface seen from both sides
  /// has a triangle for each, with that side's light).
  std::vector<uint32_t> indices;
  /// Triangle ranges, one node each; empty: a single node "radiosity" with every triangle.
  std::vector<LitMeshGroup> groups;
};

/// Writes `mesh` to `path` as a .glb, atomically (a temporary file renamed over `path`). Each
/// group becomes a node with its own mesh (vertices re-indexed per group; groups without
/// triangles are left out). Throws std::invalid_argument for an inconsistent description and
/// std::runtime_error naming `path` if the file cannot be written.
void writeLitMeshGlb(const std::string& path, const LitMesh& mesh);

}  // namespace rad
