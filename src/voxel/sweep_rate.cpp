// The voxel sweep's speed alone, for `radiosity bench voxel` (radiosity/kernel_timing.h): the
// sweeps of a sample of the sphere's direction pairs, as one iteration of a solve sweeps them.
#include <radiosity/error.h>
#include <radiosity/kernel_timing.h>

#include <algorithm>
#include <chrono>

#include "voxel/direction_set.h"
#include "voxel/discrete_line_sweep.h"
#include "voxel/voxel_solver.h"
#include "voxel/voxelizer.h"

namespace rad {

VoxelSweepRate measureVoxelSweepRate(const Scene& scene, size_t voxels, int sphereRadius,
                                     size_t pairStride, int rounds,
                                     const ProgressCallback& progress) {
  VoxelizerSettings voxelizer;
  voxelizer.targetVoxels = voxels;
  const VoxelGrid grid = voxelizeScene(scene, voxelizer);
  const DirectionSet directions(sphereRadius);
  std::vector<size_t> pairs;
  for (size_t k = 0; k < directions.pairCount(); k += std::max<size_t>(pairStride, 1))
    pairs.push_back(k);
  // Records sized for the sphere's widest direction, as a solve sizes them.
  std::vector<IVec3> steps;
  for (size_t k = 0; k < directions.pairCount(); ++k) steps.push_back(directions.pairFirst(k).step);

  std::vector<DiscreteLineSweep::SentLight> sent(grid.entryCount());
  const DiscreteLineSweep::Source source = DiscreteLineSweep::packSides(
      grid, [](size_t) { return Color(1.0f); }, sent);
  std::vector<Color> gathered(grid.entryCount(), Color(0.0f));
  DiscreteLineSweep sweep(grid, {});
  sweep.reserveLines(maxLineCount(grid, steps));
  VoxelSweepRate rate;
  for (int round = 0; round < rounds; ++round) {
    const auto start = std::chrono::steady_clock::now();
    for (size_t i = 0; i < pairs.size(); ++i) {
      sweep.sweepPair(directions.pairFirst(pairs[i]), source, gathered);
      if (progress && !progress(double(size_t(round) * pairs.size() + i + 1) /
                                double(size_t(rounds) * pairs.size())))
        throw Cancelled();
    }
    rate.roundSeconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(rate.roundSeconds.begin(), rate.roundSeconds.end());
  // What a solve's stats count: the grid, the solver's arrays and the sweep's.
  VoxelSolverSettings solver;
  solver.sphereRadius = sphereRadius;
  rate.bytes = double(grid.memoryBytes() + grid.entryCount() * voxelSolverBytesPerSide(solver) +
                      sweep.workingBytes());
  rate.voxels = grid.cellCount();
  rate.sides = grid.entryCount();
  rate.directions = directions.size();
  rate.directionsSwept = 2 * pairs.size();
  // A pair visits every cell once for each of its two directions.
  rate.visitsPerRound = 2.0 * double(pairs.size()) * double(grid.cellCount());
  return rate;
}

}  // namespace rad
