// The voxel sweep's decoding of packed sides, for each instruction set Highway compiles the
// sweep's pass for (sweep_pass.cpp): a side's snorm16 normal, its half-float radiosity and its
// fixed-point centroid, each in a few vector instructions, and the 16-byte slot a look reads.
// A packed normal or radiosity (a Slot's or a RecentVoxel's first 12 bytes, a SideOrientation)
// decodes with one 8-byte load and one conversion each; the fourth lane, read from the field
// after, is dropped. Highway's HWY_SCALAR target (the fallback where GCC's EMU128 is broken)
// has one-lane vectors: there the same values are computed a lane at a time.

// Highway's per-target include guard: this file is compiled once for every target.
#if defined(RADIOSITY_VOXEL_SWEEP_KERNELS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RADIOSITY_VOXEL_SWEEP_KERNELS_INL_H_
#undef RADIOSITY_VOXEL_SWEEP_KERNELS_INL_H_
#else
#define RADIOSITY_VOXEL_SWEEP_KERNELS_INL_H_
#endif

#include <hwy/highway.h>

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "voxel/band_scratch.h"
#include "voxel/discrete_line_sweep.h"
#include "voxel/half_float.h"

HWY_BEFORE_NAMESPACE();
namespace rad::sweep::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

#if HWY_TARGET != HWY_SCALAR
// Four lanes, the fourth dropped: the widest a Vec3 needs.
using Float4 = hn::CappedTag<float, 4>;
using Int4 = hn::CappedTag<int32_t, 4>;
using Half4 = hn::CappedTag<hwy::float16_t, 4>;
using Short4 = hn::CappedTag<int16_t, 4>;
using Ushort8 = hn::CappedTag<uint16_t, 8>;

template <class V>
Vec3 lanes(V v) {
  alignas(16) float f[4];
  hn::Store(v, Float4(), f);
  return Vec3(f[0], f[1], f[2]);
}
#endif

// The unit normal packed in the first 8 bytes of `p` (a Slot, RecentVoxel or SideOrientation).
template <typename Packed>
Vec3 slotNormal(const Packed& p) {
  static_assert(offsetof(Packed, normal) == 0 && sizeof(Packed) >= 8);
  constexpr float kUnit = 1.0f / PackedNormal::kScale;
  const auto* packed = reinterpret_cast<const int16_t*>(&p);
#if HWY_TARGET == HWY_SCALAR
  int16_t n[3];
  std::memcpy(n, packed, sizeof n);
  return Vec3(float(n[0]) * kUnit, float(n[1]) * kUnit, float(n[2]) * kUnit);
#else
  const auto n = hn::ConvertTo(Float4(), hn::PromoteTo(Int4(), hn::LoadU(Short4(), packed)));
  return lanes(hn::Mul(n, hn::Set(Float4(), kUnit)));
#endif
}

// The radiosity packed as half floats in `p` (a Slot or RecentVoxel).
template <typename Packed>
Color halfColor(const Packed& p) {
  const auto* halves = reinterpret_cast<const char*>(&p) + offsetof(Packed, radiosity);
#if HWY_TARGET == HWY_SCALAR
  uint16_t h[3];
  std::memcpy(h, halves, sizeof h);
  return Color(fromHalf(h[0]), fromHalf(h[1]), fromHalf(h[2]));
#else
  return lanes(
      hn::PromoteTo(Float4(), hn::LoadU(Half4(), reinterpret_cast<const hwy::float16_t*>(halves))));
#endif
}

// Side e's unit normal, read from the Source's arrays.
inline Vec3 sideNormal(const DiscreteLineSweep::Source& source, size_t e) {
  return slotNormal(source.normals[e]);
}

#if HWY_TARGET != HWY_SCALAR
// Side e's three half floats in the low 16-bit lanes, the others zero: its 6 bytes read as
// 4 + 2 (its array ends where its last side does).
inline auto sentHalves(const DiscreteLineSweep::Source& source, size_t e) {
  uint32_t low;
  uint16_t high;
  std::memcpy(&low, source.sides[e].radiosity, sizeof low);
  std::memcpy(&high, source.sides[e].radiosity + 2, sizeof high);
  const hn::CappedTag<uint32_t, 4> words;
  return hn::InsertLane(hn::BitCast(Ushort8(), hn::InsertLane(hn::Zero(words), 0, low)), 2, high);
}
#endif

// The radiosity side e sends (over the Source's scale).
inline Color sideLight(const DiscreteLineSweep::Source& source, size_t e) {
#if HWY_TARGET == HWY_SCALAR
  const uint16_t* h = source.sides[e].radiosity;
  return Color(fromHalf(h[0]), fromHalf(h[1]), fromHalf(h[2]));
#else
  const hn::Rebind<hwy::float16_t, Float4> halves;
  return lanes(hn::PromoteTo(Float4(), hn::BitCast(halves, hn::LowerHalf(sentHalves(source, e)))));
#endif
}

#if HWY_TARGET != HWY_SCALAR
// A slot from its normal and radiosity (`packed`'s first 12 bytes) and its offset, put together
// in one register: kept in memory it is one store, from which a look's 8-byte reads of normal
// and radiosity are served at once (written field by field, each such read waited for the
// stores to reach the cache).
template <class V>
Slot slotOf(V packed, float offset) {
  const hn::CappedTag<uint32_t, 4> words;
  const auto v = hn::InsertLane(hn::BitCast(words, packed), 3, std::bit_cast<uint32_t>(offset));
  alignas(16) uint32_t bytes[4];
  hn::Store(v, words, bytes);
  Slot slot;
  std::memcpy(&slot, bytes, sizeof slot);
  return slot;
}
#endif

// Side e, whose centroid is c, as a look meets it: its plane and the radiosity it sends.
inline Slot sideSlot(const DiscreteLineSweep::Source& source, size_t e, const Vec3& c) {
  static_assert(offsetof(Slot, radiosity) == 6 && offsetof(Slot, offset) == 12);
  const float offset = glm::dot(slotNormal(source.normals[e]), c);
#if HWY_TARGET == HWY_SCALAR
  Slot slot;
  std::memcpy(slot.normal, &source.normals[e], sizeof slot.normal);
  std::memcpy(slot.radiosity, source.sides[e].radiosity, sizeof slot.radiosity);
  slot.offset = offset;
  return slot;
#else
  // The normal in 16-bit lanes 0-2, the radiosity moved up into lanes 3-5.
  const Ushort8 d;
  const auto* packed = reinterpret_cast<const uint16_t*>(&source.normals[e]);
  const auto normal = hn::ZeroExtendVector(d, hn::LoadU(hn::Half<Ushort8>(), packed));
  const auto halves = hn::ShiftLeftBytes<6>(d, sentHalves(source, e));
  return slotOf(hn::IfThenElse(hn::FirstN(d, 3), normal, halves), offset);
#endif
}

// The line's recent voxel as a slot, given it holds one side (its record's normal and
// radiosity lie as a slot's do).
inline Slot recentSideSlot(const LineState& state) {
  static_assert(offsetof(RecentVoxel, radiosity) == offsetof(Slot, radiosity));
  const float offset = glm::dot(slotNormal(state.recent), state.recent.centroid);
#if HWY_TARGET == HWY_SCALAR
  Slot slot;
  std::memcpy(&slot, &state.recent, offsetof(Slot, offset));
  slot.offset = offset;
  return slot;
#else
  const hn::CappedTag<uint32_t, 4> words;
  return slotOf(hn::LoadU(words, reinterpret_cast<const uint32_t*>(&state.recent)), offset);
#endif
}

// Side e's centroid, as the grid's centroidOf gives it (where 256-bit vectors are: its three
// fields shifted into three 64-bit lanes at once, their low halves converted and scaled with
// one multiply-add, fused where the grid's is, as in a build for x86-64-v3).
template <typename View>
Vec3 centroidOf(const View& view, size_t e) {
#if HWY_CAP_GE256
  const hn::Full256<uint64_t> d64;
  alignas(32) static constexpr uint64_t kShifts[4] = {0, 21, 42, 0};
  constexpr uint64_t kMask = (uint64_t(1) << 21) - 1;
  const auto fields =
      hn::And(hn::Set(d64, view.centroid[e].bits) >> hn::Load(d64, kShifts), hn::Set(d64, kMask));
  const auto steps = hn::BitCast(Int4(), hn::TruncateTo(hn::Full128<uint32_t>(), fields));
  // The origin and the step, one load: (x, y, z, step).
  static_assert(offsetof(View, pointStep) == offsetof(View, pointOrigin) + 3 * sizeof(float));
  const auto frame = hn::LoadU(Float4(), &view.pointOrigin.x);
  return lanes(hn::MulAdd(hn::ConvertTo(Float4(), steps), hn::Broadcast<3>(frame), frame));
#else
  return unpack(view.centroid[e], view.pointOrigin, view.pointStep);
#endif
}

}  // namespace rad::sweep::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // RADIOSITY_VOXEL_SWEEP_KERNELS_INL_H_
