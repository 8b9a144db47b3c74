// The voxel sweep's pass, compiled once for every instruction set Highway targets (this file is
// included again by foreach_target.h for each) and dispatched at run time to the widest the
// processor has.

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "voxel/sweep_pass.cpp"
#include "voxel/sweep_pass.h"

#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include "voxel/line_visit-inl.h"
#include "voxel/pass_order-inl.h"

HWY_BEFORE_NAMESPACE();
namespace rad::sweep::HWY_NAMESPACE {

template <bool kTangentCorrection>
void pass(const BandPass& p) {
  const VoxelGrid& grid = p.cells.grid;
  const PassView view{grid.cellEntryBegin.data(),
                      grid.centroid.data(),
                      grid.origin,
                      grid.pointStep,
                      p.source,
                      &p.visibility,
                      p.gathered,
                      &p.scratch.waiting,
                      &p.scratch.later,
                      p.unit,
                      p.weight,
                      p.visibility.planeTolerance(),
                      p.visibility.edgeTolerance()};
  LineState* const lines = p.scratch.recordsFor(grid, p.band.lineCount, p.bandLines);
  p.scratch.waiting.clear();  // the band's lines are new: none of their sides waits
  const uint16_t stamp = p.scratch.stamp;
  const uint32_t firstLine = p.band.firstLine;
  // Line records are scattered over the band's (up to a twenty-fourth of the scene's
  // cross-section), and the cells' own data is read in an order that jumps back row by row: fetch
  // both kAhead cells ahead of the visit so that the misses overlap instead of queueing.
  constexpr uint32_t kAhead = 32, kMask = kAhead - 1;
  uint32_t ringCell[kAhead], ringLine[kAhead];
  int32_t ringDominant[kAhead];
  uint32_t count = 0;
  auto visit = [&](uint32_t i) {
    const uint32_t cell = ringCell[i], begin = view.entryBegin[cell];
    LineState& state = lines[ringLine[i]];
    if (state.stamp != stamp) {
      state.stamp = stamp;
      state.recentRef = state.olderRef[0] = state.olderRef[1] = kNoVoxel;
      state.pending = state.pendingLink = kNoPending;
    }
    if (view.entryBegin[cell + 1] - begin == 1)
      visitSingleSide<kTangentCorrection>(view, begin, state, ringDominant[i]);
    else
      visitSeveralSides<kTangentCorrection>(view, cell, state, ringDominant[i]);
  };
  forEachCellInPassOrder(
      p.cells, p.step, p.band, [&](uint32_t cell, uint32_t line, int32_t dominant) {
        line -= firstLine;  // the band's records hold its lines from firstLine on
        __builtin_prefetch(&lines[line], 1);
        const uint32_t first = view.entryBegin[cell];
        __builtin_prefetch(&view.centroid[first]);
        __builtin_prefetch(&view.gathered[first], 1);
        __builtin_prefetch(&view.source.normals[first]);
        __builtin_prefetch(&view.source.sides[first]);
        const uint32_t i = count++ & kMask;
        if (count > kAhead) visit(i);
        ringCell[i] = cell, ringLine[i] = line, ringDominant[i] = dominant;
      });
  for (uint32_t i = count > kAhead ? count - kAhead : 0; i < count; ++i) visit(i & kMask);
  p.scratch.later.addTo(view.gathered);
}

void sweepBand(const BandPass& p) {
  if (p.tangentCorrection)
    pass<true>(p);
  else
    pass<false>(p);
}

}  // namespace rad::sweep::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace rad::sweep {

HWY_EXPORT(sweepBand);

void sweepBand(const BandPass& pass) {
  HWY_DYNAMIC_DISPATCH(sweepBand)(pass);
}

std::vector<int64_t> sweepTargets() {
  return hwy::SupportedAndGeneratedTargets();  // this file's targets: the pass's
}

}  // namespace rad::sweep
#endif
