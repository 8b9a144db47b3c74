#pragma once
// Timings of the kernels inside the methods, which no solve's stats show apart: what
// `radiosity bench` reports for the voxel sweep, the cube probes of moving objects and the
// patch method's direct light. Each runs its kernel as a solve runs it, on all threads.

#include <radiosity/progress.h>
#include <radiosity/ray_caster.h>
#include <radiosity/scene.h>
#include <radiosity/surface_radiance.h>

#include <cstddef>
#include <span>
#include <vector>

namespace rad {

/// The voxel sweep's speed on one grid (measureVoxelSweepRate).
struct VoxelSweepRate {
  size_t voxels = 0, sides = 0;
  size_t directions = 0;             ///< of the sphere of radius R
  size_t directionsSwept = 0;        ///< of them, in each round
  std::vector<double> roundSeconds;  ///< each round's time, fastest first
  double visitsPerRound = 0.0;       ///< voxel-direction visits a round
  double bytes = 0.0;  ///< what a solve of this grid holds (the grid, the solver's and the sweep's)
};

/// The sweeps of every `pairStride`-th direction pair of the sphere of radius `sphereRadius`
/// (all octants and dominant axes, in the sphere's own mix) over `scene` voxelized at about
/// `voxels` voxels, on all threads, `rounds` times; every side sends unit radiosity. A sweep's
/// rate depends on the grid and on the directions' mix, not on how many directions there are,
/// so a sample of the sphere gives the rate of a whole iteration within a few percent. Throws
/// Cancelled when `progress` returns false.
VoxelSweepRate measureVoxelSweepRate(const Scene& scene, size_t voxels, int sphereRadius,
                                     size_t pairStride, int rounds,
                                     const ProgressCallback& progress = {});

/// A cube probe's cost (measureCubeProbe), in milliseconds.
struct CubeProbeTiming {
  double captureMs = 0.0;  ///< one capture of the view, the mean of 20
  /// The irradiance of every normal by each way (exact, harmonic, pattern, in ProbeIrradiance's
  /// order), in parallel: the mean of 2 passes (exact) or 20.
  double irradianceMs[3] = {0.0, 0.0, 0.0};
};

/// Captures a cube probe of `resolution` texels a face at `centre` in `radiance` (seen through
/// `caster`), then evaluates its irradiance for every one of `normals` by each way.
CubeProbeTiming measureCubeProbe(const RayCaster& caster, const SurfaceRadiance& radiance,
                                 const Vec3& centre, int resolution, std::span<const Vec3> normals);

/// One pass of the lights' direct light over every patch (measurePatchDirectLight).
struct DirectLightPassTiming {
  size_t patches = 0;
  double medianMs = 0.0;  ///< of 21 passes
};

/// The scene's lights' direct light on every patch of a mesh of about `patches` patches, by the
/// midpoint rule's `pointsPerPatch` points with a shadow ray each: what the patch method pays for
/// its first shot, and relighting for every frame of moved lights.
DirectLightPassTiming measurePatchDirectLight(const Scene& scene, size_t patches,
                                              int pointsPerPatch);

}  // namespace rad
