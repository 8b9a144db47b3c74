#include <radiosity/cache_directory.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

namespace rad {

namespace {

bool isCacheFile(const std::filesystem::path& file) {
  const std::string name = file.filename().string(), ext = file.extension().string();
  constexpr std::array<const char*, 4> kPrefixes = {"masterff-", "formfactors-", "voxel-",
                                                    "pathtrace-"};
  return (ext == ".bin" || ext == ".checkpoint") &&
         std::any_of(kPrefixes.begin(), kPrefixes.end(),
                     [&](const char* prefix) { return name.rfind(prefix, 0) == 0; });
}

}  // namespace

uint64_t trimCacheDirectory(const std::filesystem::path& dir, uint64_t maxBytes) {
  struct Entry {
    std::filesystem::path path;
    std::filesystem::file_time_type used;
    uint64_t bytes;
  };
  std::vector<Entry> entries;
  uint64_t total = 0;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code fileError;
    if (!isCacheFile(it->path()) || !it->is_regular_file(fileError)) continue;
    const uint64_t bytes = it->file_size(fileError);
    const auto used = it->last_write_time(fileError);
    if (fileError) continue;
    entries.push_back({it->path(), used, bytes});
    total += bytes;
  }
  std::sort(entries.begin(), entries.end(),
            [](const Entry& a, const Entry& b) { return a.used < b.used; });
  uint64_t removed = 0;
  for (const Entry& e : entries) {
    if (total - removed <= maxBytes) break;
    std::error_code removeError;
    if (std::filesystem::remove(e.path, removeError)) removed += e.bytes;
  }
  return removed;
}

void touchCacheFile(const std::filesystem::path& file) {
  std::error_code ignored;
  std::filesystem::last_write_time(file, std::filesystem::file_time_type::clock::now(), ignored);
}

}  // namespace rad
