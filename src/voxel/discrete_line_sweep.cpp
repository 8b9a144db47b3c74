#include "voxel/discrete_line_sweep.h"

#include <radiosity/error.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <string>

#include "voxel/half_colors.h"
#include "voxel/half_float.h"
#include "voxel/sweep_pass.h"

namespace rad {

DiscreteLineSweep::DiscreteLineSweep(const VoxelGrid& grid, const SweepSettings& settings)
    : grid_(grid),
      settings_(settings),
      visibility_(std::make_shared<const SideVisibility>(grid)),
      bands_(grid) {
  for (uint32_t x = 0; x < uint32_t(grid.dims.x); ++x)
    if (grid.slabRowBegin[x] < grid.slabRowBegin[x + 1]) occupiedSlabs_.push_back(x);
  // A line's record holds its first waiting side as a 29-bit entry index.
  if (grid.entryCount() >= sweep::kNoPending)
    throw InputError("voxel grid", std::to_string(grid.entryCount()) +
                                       " voxel sides exceed the sweep's limit of " +
                                       std::to_string(sweep::kNoPending - 1) +
                                       "; use a larger voxel size");
}

size_t DiscreteLineSweep::threadCount() {
  return std::min(size_t(std::max(1, tbb::this_task_arena::max_concurrency())),
                  tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

size_t DiscreteLineSweep::workingBytesFor(const VoxelGrid& grid, size_t lines) {
  const size_t threads = threadCount();
  const size_t sampleBytes = threads > 1 ? LineBands::kMostSampleBytes : 0;
  return sampleBytes + SideVisibility::maskBytesFor(grid) +
         threads * sweep::BandScratch::bytesFor(grid, bandLineCapacity(grid, lines));
}

size_t DiscreteLineSweep::workingBytes() const {
  size_t threads = 0;
  for (const sweep::BandScratch& scratch : scratch_) threads += scratch.bytes();
  return threads + bands_.sampleBytes() + visibility_->foldBytes();
}

void DiscreteLineSweep::prepareLines(const IVec3& step, const LineOffset& offset) {
  table_.prepare(grid_, step, offset);
  // Without a reservation (a sweep of a single direction), bands are sized for this one.
  reserveLines(table_.lineCount());
}

DiscreteLineSweep::Source DiscreteLineSweep::packSides(const VoxelGrid& grid,
                                                       const std::function<Color(size_t)>& sends,
                                                       std::span<SentLight> sides) {
  // A group's mean is at most its largest member: the largest side bounds every slot.
  const float scale = halfScaleFor(largestComponent(sides.size(), sends));
  const float inverse = 1.0f / scale;  // a power of two: exact
  for (size_t begin = 0; begin < sides.size();) {
    size_t end = begin + 1;
    while (end < sides.size() && grid.orientation[end].sharesPrevious) ++end;
    Color b = sends(begin);
    if (end - begin > 1) {
      Vec3d sum(0.0);
      double area = 0.0;
      for (size_t e = begin; e < end; ++e) {
        sum += double(grid.areaOf(e)) * Vec3d(e == begin ? b : sends(e));
        area += grid.areaOf(e);
      }
      if (area > 0.0) b = Color(sum / area);
    }
    b *= inverse;
    for (size_t e = begin; e < end; ++e)
      for (int k = 0; k < 3; ++k) sides[e].radiosity[k] = toHalf(b[k]);
    begin = end;
  }
  return {grid.orientation.data(), sides, scale};
}

void DiscreteLineSweep::sweepPair(const DiscreteDirection& direction, const Source& source,
                                  std::span<Color> gathered, const LineOffset& offset) {
  prepareLines(direction.step, offset);
  const size_t threads = threadCount();
  bands_.cut(table_, bandCountFor(threads, table_.zDominant()), bandLines_);
  const float weight = float(direction.solidAngle / 3.14159265358979323846) * source.scale;
  const Vec3 unit(direction.unit);
  const sweep::PassCells cells{grid_, table_, occupiedSlabs_};
  const std::vector<LineBand>& bands = bands_.bands();
  auto sweepBand = [&](size_t b) {
    sweep::sweepBand({cells, *visibility_, bands[b], direction.step, unit, weight,
                      settings_.tangentCorrection, source, gathered.data(), scratch_.local(),
                      bandLines_});
  };
  if (threads == 1) {
    for (size_t b = 0; b < bands.size(); ++b) sweepBand(b);
    return;
  }
  // Bands touch disjoint line records and sides (a side gathers from its own line only).
  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, bands.size(), 1),
      [&](const tbb::blocked_range<size_t>& r) {
        for (size_t b = r.begin(); b != r.end(); ++b) sweepBand(b);
      },
      tbb::simple_partitioner());
}

}  // namespace rad
