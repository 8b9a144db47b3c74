// The voxel sweep's visit of a cell on its line: what its sides see behind them along the line,
// what the sides waiting on the line from before see in it, and the line's record after it.
//
// What a voxel side sees along its line: the light travelling along s reaches side e from the
// first voxel behind it whose surface the backward ray from e's centroid really meets
// (side_visibility.h). One traversal along s serves s and -s: a side facing back looks at the
// voxels behind it at once; a side facing ahead waits on its line's record until the next voxel
// arrives, and its light is added later in batches (it was visited long ago). A voxel is looked
// through when the ray only grazes its surface: this is the paper's tangent correction made
// exact per side; the voxels of a floor do not hide each other from a wall at a grazing angle,
// and the sides of a thin wall never see through it.

// Highway's per-target include guard: this file is compiled once for every target.
#if defined(RADIOSITY_VOXEL_LINE_VISIT_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RADIOSITY_VOXEL_LINE_VISIT_INL_H_
#undef RADIOSITY_VOXEL_LINE_VISIT_INL_H_
#else
#define RADIOSITY_VOXEL_LINE_VISIT_INL_H_
#endif

#include <hwy/highway.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "voxel/band_scratch.h"
#include "voxel/discrete_line_sweep.h"
#include "voxel/side_visibility.h"
#include "voxel/sweep_kernels-inl.h"

HWY_BEFORE_NAMESPACE();
namespace rad::sweep::HWY_NAMESPACE {

/// What a pass reads and writes, as raw pointers the compiler can keep in registers.
struct PassView {
  const uint32_t* entryBegin;
  const PackedPoint* centroid;
  Vec3 pointOrigin;
  float pointStep;
  DiscreteLineSweep::Source source;
  const SideVisibility* visibility;
  Color* gathered;
  WaitingList* waiting;
  DeferredGathers* later;
  Vec3 unit;
  float weight, tolerance, edge;
};

/// A zero normal marks a cell of several sides, in a slot or a record.
inline bool holdsCell(const int16_t normal[3]) {
  return (normal[0] | normal[1] | normal[2]) == 0;
}
/// The slot standing for a cell of several sides (zero normal, the cell's index in `offset`).
inline Slot cellSlot(uint32_t cell) {
  Slot slot{};
  std::memcpy(&slot.offset, &cell, sizeof cell);
  return slot;
}
inline uint32_t slotCell(float offset) {
  uint32_t cell;
  std::memcpy(&cell, &offset, sizeof cell);
  return cell;
}
/// The recent voxel as a slot (the cell's index for a cell of several sides).
inline Slot recentSlot(const LineState& state) {
  return holdsCell(state.recent.normal) ? cellSlot(state.recentRef & ~kCellRef)
                                        : recentSideSlot(state);
}

/// What a side (its centroid, passed, not looked up: the side may have been visited long ago,
/// and the caller holds it; its normal, which `normal()` gives) sees in slot s, whose centroid
/// `slotCentroid()` gives when it holds one side; `light` gets the source's radiosity when it
/// is Source. The two are called only when needed: when a back is met, or s holds a cell.
template <typename Normal, typename SlotCentroid>
Sight look(const PassView& view, const Vec3& centroid, const Normal& normal, const Slot& s,
           const Vec3& unit, Color& light, const SlotCentroid& slotCentroid) {
  if (holdsCell(s.normal)) {
    uint32_t side = 0;
    const Sight sight = view.visibility->look(centroid, normal(), slotCell(s.offset), unit, side);
    if (sight == Sight::Source) light = sideLight(view.source, side);
    return sight;
  }
  const Vec3 n = slotNormal(s);
  const Sight sight =
      planeSight(glm::dot(n, centroid) - s.offset, glm::dot(n, unit), view.tolerance);
  if (sight == Sight::Source) light = halfColor(s);
  if (sight == Sight::Blocked && passesConvexEdge(normal(), centroid, slotCentroid(), view.edge))
    return Sight::Through;
  return sight;
}

/// What a side sees past the line's recent voxel (the two voxels before it).
inline Sight lookOlder(const PassView& view, const Vec3& centroid, const Vec3& normal,
                       const LineState& state, Color& light) {
  // With the tangent correction a grazed voxel is looked through: the two voxels before it
  // decide. The nearer is read from the record's slot where it lies, the other from its
  // reference: a slot put together here and read back at once stalls on its partial stores
  // (45% of this function's time when the first was copied out of the record).
  if (state.olderRef[0] == kNoVoxel) return Sight::Through;
  const Sight sight = look(
      view, centroid, [&] { return normal; }, state.older, view.unit, light,
      [&] { return centroidOf(view, state.olderRef[0]); });
  const uint32_t ref = state.olderRef[1];
  if (sight != Sight::Through || ref == kNoVoxel) return sight;
  if (ref & kCellRef) {
    uint32_t side = 0;
    const Sight cellSight =
        view.visibility->look(centroid, normal, ref & ~kCellRef, view.unit, side);
    if (cellSight == Sight::Source) light = sideLight(view.source, side);
    return cellSight;
  }
  const Vec3 n = sideNormal(view.source, ref), refCentroid = centroidOf(view, ref);
  const Sight sideSight =
      planeSight(glm::dot(n, centroid - refCentroid), glm::dot(n, view.unit), view.tolerance);
  if (sideSight == Sight::Source) light = sideLight(view.source, ref);
  if (sideSight == Sight::Blocked && passesConvexEdge(normal, centroid, refCentroid, view.edge))
    return Sight::Through;
  return sideSight;
}

/// Queues light for side e (a side that waited) in the pass's deferred batch.
inline void gatherLater(const PassView& view, uint32_t e, const Color& light) {
  // The side's accumulator is fetched now as well, up to a batch before it is added to: the
  // batch's fetches ahead alone leave part of the misses' wait (1.005-1.017x, one and two
  // threads, runs side by side).
  __builtin_prefetch(&view.gathered[e], 1);
  DeferredGathers& later = *view.later;
  later.items[later.count++] = {e, light};
  if (later.count == DeferredGathers::kCapacity) later.addTo(view.gathered);
}

/// Makes side e wait on the line for light from ahead; `sameRun` when the side waiting before
/// it is the previous voxel of its run.
inline void wait(const PassView& view, LineState& state, uint32_t e, bool sameRun) {
  const uint32_t next = state.pending == kNoPending
                            ? kNoPending
                            : view.waiting->take(state.pending, state.pendingLink);
  state.pendingLink = next | (sameRun ? kSameRun : 0u);
  state.pending = e;
}

/// Makes `ref` (an entry or kCellRef | cell) the line's recent voxel, pushing the one before
/// back unless the run continues; the caller has set `older` to that voxel's slot and then
/// writes the new recent voxel's data.
inline void becomeRecent(LineState& state, uint32_t ref, int32_t dominant, bool continues) {
  // A run along the same planes stays one voxel (its nearest): only a new run pushes the
  // voxels before it back.
  if (!continues) {
    state.olderRef[1] = state.olderRef[0];
    state.olderRef[0] = state.recentRef;
  }
  state.recentRef = ref;
  state.lastDominant = int16_t(dominant);
}

/// Lets the sides waiting on the line's record look at the voxel in `slot` (whose centroid is
/// `slotCentroid` when it holds one side).
template <bool kTangentCorrection>
void resolvePending(const PassView& view, LineState& state, const Slot& slot,
                    const Vec3& slotCentroid) {
  // The sides waiting for light from ahead meet a new voxel (the nearest of its run): each sees
  // its source, is blocked, or, grazing it, waits for the next one (with the tangent correction,
  // up to kLookThrough voxels, as many as a look back passes). The first waiting side is often
  // the line's recent voxel, whose centroid the record holds.
  const Vec3 back = -view.unit;
  uint32_t m = state.pending, link = state.pendingLink;
  uint32_t waiting = kNoPending, waitingLink = kNoPending;
  Sight sight = Sight::Through;
  Color light(0.0f);
  float weight = 0.0f;
  bool sameRunAsBefore = false, keptBefore = false;
  while (true) {
    if (!sameRunAsBefore) {
      const bool recent = m == state.recentRef;
      const Vec3 centroid = recent ? state.recent.centroid : centroidOf(view, m);
      // The normal of a side visited long ago is read only when needed (a miss).
      const auto normal = [&] {
        return recent ? slotNormal(state.recent) : sideNormal(view.source, m);
      };
      sight = look(view, centroid, normal, slot, back, light, [&] { return slotCentroid; });
      if (sight == Sight::Source) weight = glm::dot(normal(), view.unit) * view.weight;
    }
    const uint32_t depth = link >> kDepthShift;
    if (sight == Sight::Source) {
      gatherLater(view, m, light * weight);
    } else if (kTangentCorrection && sight == Sight::Through && depth < kLookThrough) {
      // Kept, in reverse order: the run mark now links it to the side kept before it.
      const uint32_t next =
          waiting == kNoPending ? kNoPending : view.waiting->take(waiting, waitingLink);
      waitingLink =
          next | ((depth + 1) << kDepthShift) | (sameRunAsBefore && keptBefore ? kSameRun : 0u);
      waiting = m;
      keptBefore = true;
    } else {
      keptBefore = false;
    }
    sameRunAsBefore = (link & kSameRun) != 0;
    const uint32_t next = link & kNoPending;
    if (next == kNoPending) break;
    const WaitingSide side = view.waiting->giveBack(next);
    m = side.entry;
    link = side.link;
  }
  state.pending = waiting;
  state.pendingLink = waitingLink;
}

/// The sides waiting on the line meet side e (centroid c, normal n, facing = n . unit), the
/// line's new voxel. Most often the one side waiting is the recent voxel, a wall across the
/// room: it looks at e's plane from its centroid, which the record holds, unless it grazes e
/// (then the general rule lets it wait on).
template <bool kTangentCorrection>
void answerWaitingSides(const PassView& view, LineState& state, uint32_t e, const Vec3& n,
                        const Vec3& c, float facing, const Vec3& recentNormal, float recentFacing) {
  const RecentVoxel& recent = state.recent;
  const bool recentIsSide = (state.recentRef & kCellRef) == 0;  // kNoVoxel has the bit too
  Sight recentSight = planeSight(glm::dot(n, recent.centroid - c), -facing, view.tolerance);
  if (recentSight == Sight::Blocked && recentIsSide &&
      passesConvexEdge(recentNormal, recent.centroid, c, view.edge))
    recentSight = Sight::Through;
  if (state.pending == state.recentRef && state.pendingLink == kNoPending && recentIsSide &&
      recentSight != Sight::Through) {
    if (recentSight == Sight::Source)
      gatherLater(view, state.pending, sideLight(view.source, e) * (recentFacing * view.weight));
    state.pending = kNoPending;
  } else {
    resolvePending<kTangentCorrection>(view, state, sideSlot(view.source, e, c), c);
  }
}

/// Lets side e, its cell's only one, look back along the line, then makes it the line's recent
/// voxel.
template <bool kTangentCorrection>
void visitSingleSide(const PassView& view, uint32_t e, LineState& state, int32_t dominant) {
  // Most cells hold one side and most recent voxels are one side: the plane test against the
  // recent voxel serves the look back, the run test and the waiting sides, computed once.
  const Vec3 n = sideNormal(view.source, e);
  const Vec3 c = centroidOf(view, e);
  const float facing = glm::dot(n, view.unit);  // < 0: e looks back along the line, > 0: ahead
  const RecentVoxel& recent = state.recent;
  const bool hasRecent = state.recentRef != kNoVoxel;
  const bool recentIsSide = (state.recentRef & kCellRef) == 0;  // kNoVoxel has the bit too
  Vec3 recentNormal(0.0f);
  float height = 0.0f, recentFacing = 0.0f;
  bool inRecentPlane = false;
  if (recentIsSide) {
    recentNormal = slotNormal(recent);
    height = glm::dot(recentNormal, c - recent.centroid);
    recentFacing = glm::dot(recentNormal, view.unit);
    inRecentPlane = std::abs(height) <= view.tolerance;
  }
  // A run along the same plane stays one voxel: its nearest.
  const bool continues = kTangentCorrection && inRecentPlane &&
                         std::abs(dominant - state.lastDominant) == 1 &&
                         glm::dot(recentNormal, n) > kSamePlaneCos;
  if (!continues && state.pending != kNoPending)
    answerWaitingSides<kTangentCorrection>(view, state, e, n, c, facing, recentNormal,
                                           recentFacing);
  if (facing < 0.0f && hasRecent) {
    Color light(0.0f);
    Sight sight;
    if (recentIsSide) {
      sight = planeSight(height, recentFacing, view.tolerance);
      if (sight == Sight::Source) light = halfColor(recent);
      if (sight == Sight::Blocked && passesConvexEdge(n, c, recent.centroid, view.edge))
        sight = Sight::Through;
    } else {
      sight = look(
          view, c, [&] { return n; }, recentSlot(state), view.unit, light,
          [&] { return recent.centroid; });
    }
    if (kTangentCorrection && sight == Sight::Through) sight = lookOlder(view, c, n, state, light);
    if (sight == Sight::Source) view.gathered[e] += light * (-facing * view.weight);
  } else if (facing > 0.0f) {
    wait(view, state, e, continues && state.pending == state.recentRef);
  }
  if (!continues && hasRecent) {
    // The recent voxel becomes the older one: its slot, from the normal this visit already
    // converted (recentSlot would convert it again on every new run: 0.90x, measured).
    if (recentIsSide) {
      std::memcpy(&state.older, &recent, offsetof(Slot, offset));
      state.older.offset = glm::dot(recentNormal, recent.centroid);
    } else {
      state.older = cellSlot(state.recentRef & ~kCellRef);
    }
  }
  becomeRecent(state, e, dominant, continues);
  // The normal's eight bytes first: its spare lane lands where the radiosity goes.
  static_assert(offsetof(RecentVoxel, radiosity) == 6);
  std::memcpy(&state.recent, &view.source.normals[e], 8);
  std::memcpy(state.recent.radiosity, &view.source.sides[e], sizeof state.recent.radiosity);
  state.recent.centroid = c;
}

/// Lets the sides of a cell of several sides look back along the line (or within the cell),
/// then makes the cell the line's recent voxel.
template <bool kTangentCorrection>
void visitSeveralSides(const PassView& view, uint32_t cell, LineState& state, int32_t dominant) {
  const Vec3& unit = view.unit;
  const DiscreteLineSweep::Source& source = view.source;
  const SideVisibility& visibility = *view.visibility;
  const Slot slot = cellSlot(cell);
  // A run of cells holding the same planes stays one voxel.
  const bool continues = kTangentCorrection && state.recentRef != kNoVoxel &&
                         std::abs(dominant - state.lastDominant) == 1 &&
                         holdsCell(state.recent.normal) &&
                         visibility.continuesPlanes(cell, state.recentRef & ~kCellRef);
  if (!continues && state.pending != kNoPending)
    resolvePending<kTangentCorrection>(view, state, slot, Vec3(0.0f));  // a cell: no centroid
  const uint32_t begin = view.entryBegin[cell], end = view.entryBegin[cell + 1];
  const SideVisibility::CellFolds folds = visibility.foldsOf(cell);
  const bool hasRecent = state.recentRef != kNoVoxel;
  const Slot recent = hasRecent ? recentSlot(state) : Slot{};  // what the sides facing back meet
  for (uint32_t e = begin; e < end; ++e) {
    const Vec3 normal = sideNormal(source, e);
    const float facing = glm::dot(normal, unit);
    if (facing == 0.0f) continue;
    const float w = std::abs(facing) * view.weight;
    // The cell's own other sides first (the faces of an inner edge see each other).
    uint32_t own = 0;
    if (folds.hasFold(e) &&
        visibility.lookWithinCell(e, folds, facing < 0.0f ? unit : -unit, own)) {
      view.gathered[e] += sideLight(source, own) * w;
    } else if (facing > 0.0f) {
      wait(view, state, e, false);
    } else if (hasRecent) {
      Color light(0.0f);
      const Vec3 c = centroidOf(view, e);
      Sight sight = look(
          view, c, [&] { return normal; }, recent, unit, light,
          [&] { return state.recent.centroid; });
      if (kTangentCorrection && sight == Sight::Through)
        sight = lookOlder(view, c, normal, state, light);
      if (sight == Sight::Source) view.gathered[e] += light * w;
    }
  }
  if (!continues && hasRecent) state.older = recent;
  becomeRecent(state, kCellRef | cell, dominant, continues);
  state.recent.normal[0] = state.recent.normal[1] = state.recent.normal[2] = 0;
}

}  // namespace rad::sweep::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // RADIOSITY_VOXEL_LINE_VISIT_INL_H_
