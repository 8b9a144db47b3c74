#pragma once
// Progress reporting for long computations. The library never prints; it calls this back.

#include <functional>

namespace rad {

/// Called with the fraction done in [0, 1], from any thread but never concurrently.
/// Return false to cancel: the computation then throws rad::Cancelled.
using ProgressCallback = std::function<bool(double fractionDone)>;

}  // namespace rad
