// The cache directory's cap: radiosity's files, least recently used first, and nothing else.
#include <gtest/gtest.h>
#include <radiosity/cache_directory.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

TEST(CacheDirectory, TrimmingRemovesTheLeastRecentlyUsedOfItsOwnFilesOnly) {
  const fs::path dir = fs::path(::testing::TempDir()) / "radiosity_cache_trim";
  fs::remove_all(dir);
  fs::create_directories(dir);
  // Four files of 1,000 bytes, used one hour apart (oldest first), and two that are not ours.
  const std::vector<std::string> ours = {"masterff-a.bin", "formfactors-b.bin",
                                         "voxel-c.checkpoint", "pathtrace-d.checkpoint"};
  const auto now = fs::file_time_type::clock::now();
  for (size_t i = 0; i < ours.size(); ++i) {
    std::ofstream(dir / ours[i]) << std::string(1000, 'x');
    fs::last_write_time(dir / ours[i], now - std::chrono::hours(4 - i));
  }
  for (const char* other : {"notes.txt", "masterff-e.txt"}) {
    std::ofstream(dir / other) << std::string(5000, 'y');
    fs::last_write_time(dir / other, now - std::chrono::hours(10));
  }
  // Using the oldest makes it the newest.
  rad::touchCacheFile(dir / "masterff-a.bin");
  EXPECT_EQ(rad::trimCacheDirectory(dir, 2500), 2000u);
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(dir)) left.push_back(e.path().filename().string());
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{"masterff-a.bin", "masterff-e.txt", "notes.txt",
                                            "pathtrace-d.checkpoint"}));
  EXPECT_EQ(rad::trimCacheDirectory(dir, 2500), 0u);
  EXPECT_EQ(rad::trimCacheDirectory(dir / "missing", 0), 0u);
  fs::remove_all(dir);
}

}  // namespace
