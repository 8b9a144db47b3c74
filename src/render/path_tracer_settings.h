#pragma once
// Checks PathTracerSettings at the library boundary.

#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/path_tracer.h>

namespace rad {

/// Throws InputError naming the bad setting and its valid range.
inline void validatePathTracerSettings(const PathTracerSettings& s) {
  if (s.samplesPerPixel < 1)
    throw InputError("path tracer", fmt::format("spp {} out of range [1, inf)", s.samplesPerPixel));
  if (s.maxDepth < 1)
    throw InputError("path tracer", fmt::format("max depth {} out of range [1, inf)", s.maxDepth));
}

}  // namespace rad
