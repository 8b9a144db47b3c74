
#include <gtest/gtest.h>
#include <radiosity/process_memory.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace {

constexpr uint64_t kMiB = uint64_t(1) << 20;

TEST(MemoryUsage, ReportsSomethingOnLinux) {
  // A running gtest binary holds at least a megabyte resident; 0 would mean parsing failed.
  EXPECT_GT(rad::currentResidentBytes(), kMiB);
  EXPECT_GE(rad::peakResidentBytes(), rad::currentResidentBytes());
}

TEST(MemoryUsage, TouchingSixtyFourMebibytesRaisesThePeak) {
  // Compared with the current RSS, not the earlier peak: an earlier test may have raised the
  // peak already, but the peak can never be below what is resident now.
  const uint64_t before = rad::currentResidentBytes();
  std::vector<unsigned char> block(64 * kMiB, 1);  // value-initialised: every page is written
  volatile unsigned char sink = block[block.size() / 2];
  (void)sink;
  const uint64_t during = rad::currentResidentBytes();
  const uint64_t peak = rad::peakResidentBytes();
  EXPECT_GE(during, before + 60 * kMiB);
  EXPECT_GE(peak, before + 60 * kMiB);
}

TEST(MemoryUsage, AvailableMemoryIsSomeOfTheMachines) {
  // Some memory is free on any machine that runs the tests, and never more than it has: MemTotal,
  // read here on its own.
  std::ifstream meminfo("/proc/meminfo");
  std::string key, unit;
  uint64_t totalKiB = 0;
  while (meminfo >> key >> totalKiB >> unit && key != "MemTotal:") {
  }
  ASSERT_EQ(key, "MemTotal:");
  const uint64_t available = rad::availableMemoryBytes();
  EXPECT_GT(available, 64 * kMiB);
  EXPECT_LE(available, totalKiB * 1024);
}

}  // namespace
