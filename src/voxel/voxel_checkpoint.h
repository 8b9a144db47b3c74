#pragma once
// A voxel solve's state after an iteration, on disk, so that a solve killed an hour in (kill -9,
// a power cut, Ctrl-C) goes on from its last whole iteration when run again, to the same answer
// bit for bit (for the same thread count). Keyed by everything the solve depends on: the scene's
// geometry, materials and lights, the grid, the solver's settings and the format's version; a
// checkpoint of anything else is never used. Written atomically after every iteration, removed
// once the solve is done.

#include <radiosity/scene.h>

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/binary_io.h"
#include "voxel/voxel_grid.h"
#include "voxel/voxel_solver.h"

namespace rad {

/// What the solve needs to go on after `iterationsDone` iterations, and what it reports of them.
struct VoxelCheckpoint {
  int iterationsDone = 0;
  std::vector<Color> irradiance;  ///< H per side so far
  std::vector<Color> bounce;      ///< the last bounce as gathered (before normalization)
  std::vector<Color> direct;      ///< the first shot's H (kept with keepDirect; else empty)
  std::vector<Vec3d> bouncePower;
  Vec3d totalPower{0.0};
  Vec3d sourcePower{0.0};  ///< the light put in: B's power before the sweeps (the residuals' unit)
  std::vector<double> residuals, iterationSeconds;
  uint64_t cellVisits = 0, shadowRays = 0;
  double directSeconds = 0.0;
};

/// The file of the checkpoint of a solve of `grid` (made from `scene`) with `lights` and
/// `settings`, in settings.checkpointDir; empty when that is empty.
std::filesystem::path voxelCheckpointFile(const Scene& scene, const VoxelGrid& grid,
                                          std::span<const Light> lights,
                                          const VoxelSolverSettings& settings);

/// Writes the checkpoint atomically; returns a warning instead of throwing when it cannot.
std::string saveVoxelCheckpoint(const std::filesystem::path& file, const VoxelCheckpoint& state);

/// The checkpoint in `file` for a grid of `sides` sides, if there is one that fits; `warning`
/// says why a file that exists was not used (cut, corrupt, another version).
std::optional<VoxelCheckpoint> loadVoxelCheckpoint(const std::filesystem::path& file, size_t sides,
                                                   std::string& warning);

}  // namespace rad
