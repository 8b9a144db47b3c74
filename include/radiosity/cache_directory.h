#pragma once
// The cache directory (--cache-dir) holds form-factor tables and checkpoints, which grow with
// every new scene; it is kept under a size cap by removing the least recently used files first.

#include <cstdint>
#include <filesystem>

namespace rad {

/// Removes radiosity's files from `dir` (form-factor tables, checkpoints: "masterff-",
/// "formfactors-", "voxel-" and "pathtrace-" files) least recently used first until they take at
/// most `maxBytes`; other files are never touched. Returns the bytes removed.
uint64_t trimCacheDirectory(const std::filesystem::path& dir, uint64_t maxBytes);

/// Marks a cache file as used now, so that trimming keeps it longer.
void touchCacheFile(const std::filesystem::path& file);

}  // namespace rad
