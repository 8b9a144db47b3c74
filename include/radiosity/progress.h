#pragma once
// Progress reporting for long computations. The library never prints; it calls this back.

#include <cstddef>
#include <functional>

namespace rad {

/// Called with the fraction done in [0, 1], from any thread but never concurrently.
/// Return false to cancel: the computation then throws rad::Cancelled.
using ProgressCallback = std::function<bool(double fractionDone)>;

/// The callback for part `part` of `parts` equal parts of a computation that reports to `whole`
/// (a solve per light group): its fractions mapped into that part's share.
inline ProgressCallback progressPart(const ProgressCallback& whole, size_t part, size_t parts) {
  if (!whole) return {};
  return [=](double fraction) { return whole((double(part) + fraction) / double(parts)); };
}

}  // namespace rad
