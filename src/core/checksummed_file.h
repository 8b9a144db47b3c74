#pragma once
// The project's binary files that a later run reads back (caches, checkpoints) start with an
// 8-byte magic and end with a checksum of everything before it; they are written atomically. A
// file that cannot be written or read is a warning to the caller, who then computes anew.

#include <filesystem>
#include <string>

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

/// Seconds between two checkpoints of a long computation (the path tracer's tiles, the patch
/// method's form-factor rows): $RADIOSITY_CHECKPOINT_SECONDS when set to a number >= 0, else 30.
double checkpointIntervalSeconds();

}  // namespace rad
