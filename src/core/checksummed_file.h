#pragma once
// The project's binary files that a later run reads back (caches, checkpoints) start with an
// 8-byte magic and end with a checksum of everything before it; they are written atomically. A
// file that cannot be written or read is a warning to the caller, who then computes anew.

#include <fmt/format.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/binary_io.h"

namespace rad {

/// Appends the checksum to `bytes` and writes them to `file` atomically, creating its directory.
/// Returns "" or a warning ("<what> not written: <why>") instead of throwing; a `file` that
/// exists and is not a regular file (a directory, a FIFO) is left alone with a warning.
std::string saveChecksummed(const std::filesystem::path& file, std::string& bytes,
                            const std::string& what);

/// A file read back: `exists` false when there is none; else its bytes, and `rejected` the reason
/// it cannot be used ("" when its magic and checksum are right).
struct ChecksummedFile {
  bool exists = false;
  std::string bytes;
  std::string rejected;
};
ChecksummedFile readChecksummed(const std::filesystem::path& file, const char (&magic)[8],
                                const std::string& what);

/// A checkpoint read back: its magic, checksum and the uint32 `version` after the magic checked,
/// then `parse(reader, out)` reads the rest (returning "" or why the content is refused: made for
/// another computation, inconsistent). nullopt when there is no file; nullopt with `warning` set
/// ("<what> <file> not used (<why>); <fallback>") when it is bad, truncated or refused.
template <typename T, typename Parse>
std::optional<T> readCheckpoint(const std::filesystem::path& file, const char (&magic)[8],
                                uint32_t version, const std::string& what,
                                const std::string& fallback, std::string& warning,
                                const Parse& parse) {
  const ChecksummedFile f = readChecksummed(file, magic, what);
  if (!f.exists) return std::nullopt;
  auto reject = [&](const std::string& why) -> std::optional<T> {
    warning = fmt::format("{} {} not used ({}); {}", what, file.string(), why, fallback);
    return std::nullopt;
  };
  if (!f.rejected.empty()) return reject(f.rejected);
  T out;
  try {
    ByteReader in(f.bytes, 8, f.bytes.size() - 8);
    if (const uint32_t v = in.get<uint32_t>(); v != version)
      return reject(fmt::format("format version {}, expected {}", v, version));
    if (const std::string why = parse(in, out); !why.empty()) return reject(why);
  } catch (const std::out_of_range&) {
    return reject("truncated");
  }
  return out;
}

/// Seconds between two checkpoints of a long computation (the path tracer's tiles, the patch
/// method's form-factor rows): $RADIOSITY_CHECKPOINT_SECONDS when set to a number >= 0, else 30.
double checkpointIntervalSeconds();

}  // namespace rad
