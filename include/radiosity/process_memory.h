#pragma once
// Resident memory of this process, for the stats file and the scaling benchmarks, and the memory
// still free for it, so that large solves can refuse or scale down before they run out. Linux
// only: read from /proc, the cgroup files and the resource limits; elsewhere they return 0.

#include <cstdint>
#include <string>

namespace rad {

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

/// Refuses a computation whose memory would not fit before anything large is allocated: throws
/// InputError(where, "<what> need about X GB and Y GB is available; <advice>") when `bytes` is
/// more than availableMemoryBytes(); passes when that is unknown.
void requireMemory(double bytes, const std::string& where, const std::string& what,
                   const std::string& advice);

}  // namespace rad
