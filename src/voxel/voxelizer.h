#pragma once
// Surface voxelization of a scene's triangles for the voxel radiosity method.
//
// A voxel belongs to a triangle when the triangle meets the voxel's closed cube (conservative
// voxelization, with a small tolerance). That makes every surface tunnel-free for 26-connected
// discrete lines: two 26-adjacent cubes share at least a corner, so a chain of them from one
// side of a closed surface to the other is a connected set that meets the surface, and the cube
// where it does is a voxel of the surface. Each voxel keeps one entry per side: triangle pieces
// are clustered by normal (within 60 degrees), and a two-sided material adds its back side.

#include <radiosity/progress.h>
#include <radiosity/scene.h>
#include <radiosity/voxel_radiosity.h>

#include <functional>
#include <span>

#include "voxel/voxel_grid.h"

namespace rad {

struct VoxelizerSettings {
  float voxelSize = 0.0f;        ///< edge length in scene units; 0: derive it from targetVoxels
  size_t targetVoxels = 200000;  ///< approximate cell count when voxelSize is 0
};

/// Voxelizes every triangle of the scene. Throws InputError if the resolution would exceed the
/// grid limit (32767 voxels per axis) or the memory this process may still allocate, or the
/// scene has no triangles.
VoxelGrid voxelizeScene(const Scene& scene, const VoxelizerSettings& settings,
                        const ProgressCallback& progress = {});

/// A piece of the surface a voxel side stands for: one triangle's part inside the voxel.
struct SidePiece {
  Vec3 centroid{0.0f};
  Vec3 normal{0.0f};  ///< the unit normal of the side of the triangle it is
  double area = 0.0;  ///< its covered area (scene units^2; coverage times area)
};

/// Called with a grid entry and its side's pieces (at least one; those of no coverage left out);
/// returns false to stop.
using SidePiecesVisitor = std::function<bool(size_t entry, std::span<const SidePiece> pieces)>;

/// Calls `visit` for every entry in [firstEntry, lastEntry) of `grid`, which voxelizeScene made
/// of `scene`, with its pieces cut again from the triangles as the grid's were, from several
/// threads at once. Holds every piece of the scene meanwhile (32 B each; throws InputError when
/// they would not fit in memory).
void forEachSidesPieces(const Scene& scene, const VoxelGrid& grid, size_t firstEntry,
                        size_t lastEntry, const SidePiecesVisitor& visit);

/// About how many surface voxels this scene has at `voxelSize` (the inverse of the above).
double expectedVoxelCount(const Scene& scene, float voxelSize);

}  // namespace rad
