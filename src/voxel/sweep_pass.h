#pragma once
// One pass of the voxel sweep over a band of lines, along a direction s and its opposite at once,
// compiled for every instruction set Highway targets and run with the widest the processor has
// (sweep_pass.cpp; the visits in line_visit-inl.h, the cells' order in pass_order-inl.h).

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "voxel/band_scratch.h"
#include "voxel/discrete_line_sweep.h"
#include "voxel/line_bands.h"
#include "voxel/line_layout.h"
#include "voxel/side_visibility.h"
#include "voxel/voxel_grid.h"

namespace rad::sweep {

/// What a pass walks: the grid's cells by slabs (those of `occupiedSlabs`, x ascending), rows and
/// cells, and the lines of the direction `table` was prepared for.
struct PassCells {
  const VoxelGrid& grid;
  const LineTable& table;
  std::span<const uint32_t> occupiedSlabs;
};

/// Everything one pass reads and writes: the band's lines along `step` (whose unit vector is
/// `unit`), the light the sides send (`source`), each side's light gathered from s and -s
/// times `weight` (added to `gathered`), and the thread's records for bands of up to
/// `bandLines` lines.
struct BandPass {
  PassCells cells;
  const SideVisibility& visibility;
  const LineBand& band;
  IVec3 step;
  Vec3 unit;
  float weight;
  bool tangentCorrection;
  const DiscreteLineSweep::Source& source;
  Color* gathered;
  BandScratch& scratch;
  size_t bandLines;
};

/// Sweeps a band with the widest instruction set the processor has (AVX-512, AVX2, ... or one
/// lane at a time).
void sweepBand(const BandPass& pass);
/// The instruction sets (Highway's targets) the pass was compiled for that this processor runs,
/// widest first: those hwy::SetSupportedTargetsForTest may choose among (tests).
std::vector<int64_t> sweepTargets();

}  // namespace rad::sweep
