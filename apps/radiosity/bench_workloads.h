#pragma once
// The fixed workloads of `radiosity bench`. Each returns its numbers as JSON, with a one-line
// "summary" for the text output.

#include <nlohmann/json.hpp>
#include <string>

#include "console.h"

namespace rad::cli {

/// The reference path tracer on the Cornell box: rays per second.
nlohmann::json benchPathTracer(Console& console);

/// The patch method's form-factor rays per second, table memory and solve times on fixed
/// workloads (the Cornell box and a furnished room at ~10k patches, the Cornell box at ~100k).
nlohmann::json benchPatch(Console& console);

/// Relighting a spot swinging through a furnished room at about `patches` patches: ms per
/// relight, the patches updated per frame, the master table's hit rate and the worst error
/// against fresh solves (bench_relight.cpp says how).
nlohmann::json benchRelight(Console& console, size_t patches, int frames = 0);

/// Probes: a cube view of `resolution` texels a face captured in the Cornell box's patch
/// solution, and a 10k-vertex object's irradiance from it by each way (bench_probe.cpp).
nlohmann::json benchProbe(Console& console, int resolution);

/// The voxel sweep on a furnished room at `voxels` voxels (the paper's 2e6 by default): every
/// `pairStride`-th direction pair of the sphere of radius R swept three times on all threads,
/// voxel-direction visits per second (the median and the fastest round), the bytes per voxel a
/// solve of that grid holds (as its stats count them), and the paper's workload (2e6 voxels,
/// R = 38, 6 iterations) extrapolated from the median rate.
nlohmann::json benchVoxel(Console& console, size_t voxels, int sphereRadius, size_t pairStride);

/// Time per sweep iteration against the voxel count (room:N at one voxel size, about 1e5 up to
/// `maxVoxels`), its log-log slope, and a table (CSV) and plot (SVG) written to `outputDirectory`.
nlohmann::json benchVoxelScaling(Console& console, int sphereRadius, size_t maxVoxels,
                                 const std::string& outputDirectory);

/// A real interior's size (atrium-textured:`detail`, 252k triangles at 180) rendered by each
/// method with its defaults, each in a process of its own: the time of each stage and its peak
/// memory.
nlohmann::json benchInterior(Console& console, int detail);

/// One voxel solve (room:16 at `voxels`, R = 12) on one process with one thread against the same
/// under `mpirun -np ranks` with one thread a rank, alternating: the parallel efficiency.
nlohmann::json benchDistributed(Console& console, int ranks, size_t voxels);

}  // namespace rad::cli
