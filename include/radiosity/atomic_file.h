#pragma once
// Writing files so that readers only ever see a complete file or none: the content goes to a
// temporary file in the target's directory (same file system, so the rename is atomic) and is
// renamed over the target once it is whole. Every output and cache writer goes through here, so
// an interrupted or failed run never leaves a truncated image, stats file or cache.

#include <filesystem>
#include <functional>
#include <span>
#include <string>

namespace rad {

/// Calls `write` with a fresh temporary path in target's directory (".<name>.tmp-<pid>-<n>"),
/// flushes the file it wrote to disk and renames it over `target`. If `write` throws, or the
/// rename fails, the temporary is removed, `target` is left as it was and the exception
/// propagates; a std::runtime_error from writing (the disk full, a device refusing) comes out
/// as an InputError with its message (an output that cannot be written, as a bad output path).
/// Throws std::runtime_error naming `target` if its directory does not exist or `write` created
/// no file, or if `target` is a directory. A target that exists and is not a
/// regular file (a device such as /dev/null, a FIFO) is written directly, not replaced.
/// Temporaries left in the directory by writers that were killed are removed. Safe to call from
/// several threads at once.
void writeFileAtomically(const std::filesystem::path& target,
                         const std::function<void(const std::filesystem::path& temporary)>& write);

/// Whether this process writes files: not in the processes of a run split among several (MPI
/// ranks past 0), which compute the same answer and leave writing it to the first. While off,
/// the writers here do nothing.
void setWritesFiles(bool writes);

/// Writes `text` byte for byte (no newline translation) to `target`, atomically.
/// Throws std::runtime_error naming `target` on failure.
void writeTextAtomically(const std::filesystem::path& target, const std::string& text);

/// Writes `bytes` to `target`, atomically. Throws std::runtime_error naming `target` on failure.
void writeBytesAtomically(const std::filesystem::path& target, std::span<const char> bytes);

}  // namespace rad
