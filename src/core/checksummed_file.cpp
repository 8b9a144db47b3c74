#include "core/checksummed_file.h"

#include <radiosity/atomic_file.h>

#include <cstdlib>
#include <cstring>

#include "core/binary_io.h"

namespace rad {

std::string saveChecksummed(const std::filesystem::path& file, std::string& bytes,
                            const std::string& what) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(file, ec);
  // writeBytesAtomically writes a device or FIFO in place (an output to /dev/stdout): a cache's
  // FIFO would wait for a reader forever, and a directory cannot be replaced.
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    return what + " not written: " + file.string() + " is not a regular file";
  put(bytes, checksum(bytes.data(), bytes.size()));
  try {
    std::filesystem::create_directories(file.parent_path());
    writeBytesAtomically(file, bytes);
  } catch (const std::exception& e) {
    return what + " not written: " + e.what();
  }
  return "";
}

ChecksummedFile readChecksummed(const std::filesystem::path& file, const char (&magic)[8],
                                const std::string& what) {
  ChecksummedFile f;
  f.exists = readWholeFile(file, f.bytes);
  if (!f.exists) return f;
  if (f.bytes.size() < 8 + 8 || std::memcmp(f.bytes.data(), magic, 8) != 0)
    f.rejected = "not a " + what;
  else if (!checksumMatches(f.bytes))
    f.rejected = "truncated or corrupt";
  return f;
}

double checkpointIntervalSeconds() {
  constexpr double kDefault = 30.0;
  const char* text = std::getenv("RADIOSITY_CHECKPOINT_SECONDS");
  if (!text) return kDefault;
  char* end = nullptr;
  const double seconds = std::strtod(text, &end);
  return end != text && *end == '\0' && seconds >= 0.0 ? seconds : kDefault;
}

}  // namespace rad
