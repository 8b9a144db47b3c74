// The voxel method's stats as every method reports them (SolveReport): the summary line the
// commands print and the numbers of the stats file's "voxel" entry.
#include <fmt/format.h>
#include <radiosity/voxel_radiosity.h>

#include <algorithm>
#include <nlohmann/json.hpp>

namespace rad {

SolveReport VoxelRadiosity::report() const {
  const VoxelRadiosityStats& v = stats();
  SolveReport r;
  const double visitsPerSecond = double(v.visits) / std::max(v.sweepSeconds, 1e-9);
  r.summary = fmt::format(
      "{} voxels ({} sides), {} directions, {} iterations, residual {:.2g}{}, {:.1f} M visits/s",
      v.voxels, v.sides, v.directions, v.residuals.size(),
      v.residuals.empty() ? 0.0 : v.residuals.back(), v.converged ? "" : " (not converged)",
      visitsPerSecond * 1e-6);
  r.voxels = v.sides;
  r.detailEdge = v.voxelSize;
  r.directions = v.directions;
  r.rays = v.shadowRays;
  r.prepareSeconds = v.voxelizeSeconds;
  r.solveSeconds = v.directSeconds + v.sweepSeconds;
  r.iterations = int(v.residuals.size());
  r.residuals = v.residuals;
  r.converged = v.converged;
  r.warnings = v.warnings;
  if (v.resumedIterations > 0)
    r.resumed = fmt::format("went on from a checkpoint: {} iteration{} were done before",
                            v.resumedIterations, v.resumedIterations == 1 ? "" : "s");
  const nlohmann::json details = {
      {"resumed_iterations", v.resumedIterations},
      {"voxel_size", v.voxelSize},
      {"cells", v.voxels},
      {"sides", v.sides},
      {"visits", v.visits},
      {"visits_per_s", visitsPerSecond},
      {"shadow_rays", v.shadowRays},
      {"sweep_threads", v.sweepThreads},
      {"tail_share", v.tailShare},
      {"later_directions", v.laterDirections},
      {"memory_bytes", v.memoryBytes},
      {"bytes_per_side", double(v.memoryBytes) / double(std::max<size_t>(v.sides, 1))},
      {"bytes_per_voxel", double(v.memoryBytes) / double(std::max<size_t>(v.voxels, 1))},
      {"seconds",
       {{"voxelize", v.voxelizeSeconds},
        {"first_shot", v.directSeconds},
        {"sweeps", v.sweepSeconds},
        {"iterations", v.iterationSeconds}}}};
  r.detailsJson = details.dump();
  return r;
}

}  // namespace rad
