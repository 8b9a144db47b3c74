#pragma once
// The scale that lets colours travel in half floats (the radiosities the voxel sweeps carry).
// Half floats hold 11 significant bits between 2^-14 and 65504: not every scene's units (a small
// bulb's radiosity passes 65504 W/m^2; a scene in other units, or a late bounce, may lie far below
// 2^-14). So a set of half colours shares one power-of-two scale chosen from its largest
// component, which costs no precision: the values are divided and multiplied back exactly.

#include <radiosity/types.h>

#include <algorithm>
#include <cstddef>

namespace rad {

/// The power of two that brings `largest` (>= 0) to at most 2^14, leaving headroom for the sums
/// of a few values; 1 when it already lies in [2^-8, 2^14], so that scenes in usual units keep
/// their values as they are.
float halfScaleFor(float largest);

/// The largest component of any colour from sends(i), i < count (0 for none).
template <typename F>
float largestComponent(size_t count, F&& sends) {
  float largest = 0.0f;
  for (size_t i = 0; i < count; ++i) {
    const Color c = sends(i);
    largest = std::max({largest, c.x, c.y, c.z});
  }
  return largest;
}

}  // namespace rad
