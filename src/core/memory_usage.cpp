#include "core/memory_usage.h"

#include <fstream>
#include <sstream>
#include <string>

namespace rad {

namespace {

// /proc/self/status lines look like "VmHWM:\t   12345 kB"; the kernel always reports kB.
uint64_t statusFieldBytes(const std::string& field) {
  std::ifstream status("/proc/self/status");
  if (!status) return 0;
  const std::string prefix = field + ":";
  std::string line;
  while (std::getline(status, line)) {
    if (line.compare(0, prefix.size(), prefix) != 0) continue;
    std::istringstream values(line.substr(prefix.size()));
    uint64_t kilobytes = 0;
    std::string unit;
    if (!(values >> kilobytes >> unit) || unit != "kB") return 0;
    return kilobytes * 1024u;
  }
  return 0;
}

}  // namespace

uint64_t peakResidentBytes() {
  return statusFieldBytes("VmHWM");
}

uint64_t currentResidentBytes() {
  return statusFieldBytes("VmRSS");
}

}  // namespace rad
