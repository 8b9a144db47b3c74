#pragma once
// Resident memory of this process, for the stats file and the scaling benchmarks, and the memory
// still free for it, so that large solves can refuse or scale down before they run out. Linux
// only: read from /proc, the cgroup files and the resource limits; elsewhere they return 0.

#include <cstdint>
#include <vector>

namespace rad {

/// Gives a vector's memory back now, before it goes out of scope: `v = {}` (an initializer-list
/// assignment) and `v.clear()` keep its capacity.
template <typename T>
void releaseMemory(std::vector<T>& v) {
  std::vector<T>().swap(v);
}

/// Peak resident set size (VmHWM) in bytes since the process started; 0 if unavailable.
uint64_t peakResidentBytes();
/// Current resident set size (VmRSS) in bytes; 0 if unavailable.
uint64_t currentResidentBytes();
/// Current virtual size (VmSize) in bytes, what an address-space limit counts; 0 if unavailable.
uint64_t virtualBytes();
/// Bytes this process can still allocate without swapping: the system's MemAvailable, or less
/// when the process's control group (a container) has a lower limit or its address-space limit
/// (ulimit -v) leaves less; 0 if unknown.
uint64_t availableMemoryBytes();

}  // namespace rad
