#pragma once
// The voxel (discrete) radiosity solver: iterations of full sweeps over the discrete sphere's
// directions, each a Jacobi step B = E + rho H(B) taken one bounce at a time, with per-voxel
// normalization, an optional first shot of direct light by shadow rays, until the light still
// bouncing is a small share of the light put in (or a cap of iterations), an estimate of the
// bounces after the last iteration, and optionally a coarser sphere for the bounces after the
// first sweep.
//
// Based on: P. Chatelier and R. Malgouyres, "A low-complexity discrete radiosity method",
// Computers & Graphics 30(1), 2006 (the sweep, six iterations), and their follow-up's remark that
// small emitters subtend fewer directions than the sphere resolves, hence the first shot.

#include <radiosity/process_share.h>
#include <radiosity/progress.h>
#include <radiosity/ray_caster.h>
#include <radiosity/scene.h>
#include <radiosity/voxel_radiosity.h>

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "voxel/discrete_line_sweep.h"
#include "voxel/voxel_grid.h"

namespace rad {

/// The solver's settings: the method's own (VoxelRadiositySettings, the one place of their
/// defaults; its voxelization fields are the voxelizer's) and what a solve of one light group
/// sets.
struct VoxelSolverSettings : VoxelRadiositySettings {
  /// A factor on each scene material's emission (0 and 1 to solve one light group's emitters
  /// alone); empty: the scene's own.
  std::vector<Color> emissionScales;

  /// Whether the solution keeps the first shot's direct irradiance apart (there is none without
  /// a first shot).
  bool keepsDirect() const { return keepDirectLight && directFirstShot; }
};

struct VoxelSolution {
  std::vector<Color> radiosity;   ///< B per entry
  std::vector<Color> irradiance;  ///< H per entry
  std::vector<Color> direct;      ///< the first shot's H per entry (with keepDirect; else empty)
  /// Per iteration: the power of the light it added to B (its bounce, reflected: the light
  /// still bouncing) over the light put in (area- and luminance-weighted).
  std::vector<double> residuals;
  /// The last residual fell below a tolerance above 0 (or no light was put in).
  bool converged = false;
  double tailShare = 0.0;  ///< share of B's power the tail estimate added
  size_t directions = 0;
  size_t laterDirections = 0;  ///< directions of the sweeps after the first
  uint64_t cellVisits = 0;     ///< voxel-direction visits of all sweeps
  uint64_t shadowRays = 0;
  double directSeconds = 0.0, sweepSeconds = 0.0;
  std::vector<double> iterationSeconds;  ///< the sweeps' time in each iteration
  size_t workingBytes = 0;    ///< solver arrays beyond the grid (accumulators, line tables)
  size_t sweepThreads = 0;    ///< threads that shared each direction's sweep
  int resumedIterations = 0;  ///< iterations a checkpoint brought (0: solved from the start)
  std::vector<std::string> warnings;  ///< a checkpoint not read or not written, and why
};

/// What the solver holds per side besides the grid and the sweep's working memory (the bounce
/// being gathered, the irradiance so far, the light sent, the normalization weights): the one
/// account of its arrays, for the memory check before a solve and the memory reported after.
uint64_t voxelSolverBytesPerSide(const VoxelSolverSettings& settings);

/// The bytes a solve of `grid` will hold beyond the grid (the solver's arrays and the sweep's,
/// its line table sized for the widest direction), known before it starts: what it holds
/// (VoxelSolution::workingBytes) or more, but for the fold planes shared with neighbouring
/// voxels, found as the sweep is made (0.4% of a solve's memory in room:16 at 2M voxels, 3% at
/// 5,000), and for the waiting sides' places where more wait at once than the sweep reserves
/// (8 a line of a band: room:16 needs at most 4.4 at 2M voxels).
uint64_t voxelSolveBytes(const VoxelGrid& grid, const VoxelSolverSettings& settings);

/// Solves the scene on a voxelization of it, lit by its emitting surfaces and `lights` (the
/// first shot's shadow rays go through `caster`). Deterministic, and the same bit for bit whatever
/// the number of threads (they share each direction, and the memory does not grow with them).
/// Throws InputError if memory would not hold the solve, before any work, and rad::Cancelled if
/// `progress` returns false.
VoxelSolution solveVoxelRadiosity(const Scene& scene, const VoxelGrid& grid,
                                  const RayCaster& caster, std::span<const Light> lights,
                                  const VoxelSolverSettings& settings,
                                  const ProgressCallback& progress = {});
/// The same under the scene's own lights, with a ray caster of its own.
VoxelSolution solveVoxelRadiosity(const Scene& scene, const VoxelGrid& grid,
                                  const VoxelSolverSettings& settings,
                                  const ProgressCallback& progress = {});

}  // namespace rad
