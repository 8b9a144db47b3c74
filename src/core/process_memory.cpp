#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/process_memory.h>
#include <sys/resource.h>

#include <algorithm>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

namespace rad {

namespace {

// /proc/self/status and /proc/meminfo lines look like "VmHWM:\t   12345 kB"; the kernel always
// reports kB.
uint64_t statusFieldBytes(const std::string& field, const char* file = "/proc/self/status") {
  std::ifstream status(file);
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

// A cgroup file holding one number of bytes; nullopt if absent or not a number ("max").
std::optional<uint64_t> cgroupBytes(const std::string& path) {
  std::ifstream file(path);
  uint64_t bytes = 0;
  if (!(file >> bytes)) return std::nullopt;
  return bytes;
}

}  // namespace

uint64_t availableMemoryBytes() {
  uint64_t available = statusFieldBytes("MemAvailable", "/proc/meminfo");
  // The process's memory control group, from /proc/self/cgroup: "0::/path" (v2) or
  // "N:memory:/path" (v1); its limit, where it has one, may be below what the system has free.
  // (An unlimited v1 group reports a limit near 2^63, above any real memory.)
  std::ifstream groups("/proc/self/cgroup");
  std::string line;
  while (std::getline(groups, line)) {
    const size_t first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    const std::string path = line.substr(second + 1);
    std::string limitFile, usageFile;
    if (controllers.empty()) {
      limitFile = "/sys/fs/cgroup" + path + "/memory.max";
      usageFile = "/sys/fs/cgroup" + path + "/memory.current";
    } else if (controllers == "memory") {
      limitFile = "/sys/fs/cgroup/memory" + path + "/memory.limit_in_bytes";
      usageFile = "/sys/fs/cgroup/memory" + path + "/memory.usage_in_bytes";
    } else {
      continue;
    }
    const std::optional<uint64_t> limit = cgroupBytes(limitFile), usage = cgroupBytes(usageFile);
    if (!limit || !usage) continue;
    const uint64_t room = *limit > *usage ? *limit - *usage : 1;  // 0 would read as unknown
    available = available == 0 ? room : std::min(available, room);
  }
  // An address-space limit (ulimit -v) counts the process's virtual size, not its resident one.
  rlimit addressSpace{};
  if (getrlimit(RLIMIT_AS, &addressSpace) == 0 && addressSpace.rlim_cur != RLIM_INFINITY) {
    const uint64_t size = virtualBytes();
    const uint64_t room = addressSpace.rlim_cur > size ? addressSpace.rlim_cur - size : 1;
    available = available == 0 ? room : std::min(available, room);
  }
  return available;
}

uint64_t peakResidentBytes() {
  return statusFieldBytes("VmHWM");
}

uint64_t currentResidentBytes() {
  return statusFieldBytes("VmRSS");
}

uint64_t virtualBytes() {
  return statusFieldBytes("VmSize");
}

void requireMemory(double bytes, const std::string& where, const std::string& what,
                   const std::string& advice) {
  const uint64_t available = availableMemoryBytes();
  if (available == 0 || bytes <= double(available)) return;
  throw InputError(where, fmt::format("{} need about {:.2f} GB and {:.2f} GB is available; {}",
                                      what, bytes / 1e9, double(available) / 1e9, advice));
}

}  // namespace rad
