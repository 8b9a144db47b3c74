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

/// About how many surface voxels this scene has at `voxelSize` (the inverse of the above).
double expectedVoxelCount(const Scene& scene, float voxelSize);

}  // namespace rad
