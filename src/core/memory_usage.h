#pragma once
// Resident memory of this process, for the stats file and the scaling benchmarks. Linux only:
// read from /proc/self/status; elsewhere the functions return 0.

#include <cstdint>

namespace rad {

/// Peak resident set size (VmHWM) in bytes since the process started; 0 if unavailable.
uint64_t peakResidentBytes();
/// Current resident set size (VmRSS) in bytes; 0 if unavailable.
uint64_t currentResidentBytes();

}  // namespace rad
