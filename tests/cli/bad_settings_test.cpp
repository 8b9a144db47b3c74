// Outputs and settings that cannot work are refused before any work, with exit 2 and a message
// naming the option, never found after an hour's solve or ended by the out-of-memory killer.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <thread>

#include "cli_run.h"
#include "core/address_space_limit.h"

namespace rad::test {
namespace {

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

const std::vector<std::string> kTinyRender = {"render", "cornell", "--method", "pathtrace", "--spp",
                                              "1",      "--width", "8",        "--height",  "8"};

std::vector<std::string> tinyRender(std::initializer_list<std::string> more) {
  std::vector<std::string> args = kTinyRender;
  args.insert(args.end(), more);
  return args;
}

TEST(BadSettings, OutputPathsAreCheckedBeforeAnyWork) {
  const fs::path dir = freshDir("output_paths");
  const std::string image = (dir / "cornell.png").string();
  // Before: a missing stats directory was found after the render, which left the image behind.
  CliResult r = run(tinyRender({"-o", image, "--stats", (dir / "no/such/stats.json").string()}));
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(has(r.err, "--stats " + (dir / "no/such/stats.json").string())) << r.err;
  EXPECT_TRUE(has(r.err, "does not exist")) << r.err;
  EXPECT_FALSE(fs::exists(image));
  r = run(tinyRender({"-o", (dir / "missing/cornell.png").string()}));
  EXPECT_EQ(r.status, 2) << r.err;
  fs::create_directories(dir / "taken.glb");
  r = run({"solve", "cornell", "--method", "patch", "--patches", "50", "--export",
           (dir / "taken.glb").string()});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(has(r.err, "is a directory")) << r.err;
  // A read-only directory (root may write anyway, so only where the mode is honoured).
  fs::create_directories(dir / "locked");
  fs::permissions(dir / "locked", fs::perms::owner_read | fs::perms::owner_exec);
  if (access((dir / "locked").c_str(), W_OK) != 0) {
    r = run(tinyRender({"-o", (dir / "locked/x.png").string()}));
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_TRUE(has(r.err, "cannot write its directory")) << r.err;
  }
  fs::permissions(dir / "locked", fs::perms::owner_all);
  EXPECT_EQ(fs::directory_iterator(dir / "locked"), fs::directory_iterator());
}

TEST(BadSettings, StatsIntoAPipeAreWrittenThroughIt) {
  const fs::path dir = freshDir("stats_pipe");
  const fs::path fifo = dir / "stats";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] { received = readBytes(fifo.string()); });
  const CliResult r = run(tinyRender({"-o", (dir / "x.png").string(), "--stats", fifo.string()}));
  reader.join();
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_EQ(nlohmann::json::parse(received).at("method"), "pathtrace");
}

TEST(BadSettings, SettingsThatCannotFitAreRefusedByTheirMessage) {
  // Under an address-space limit of 256 MB more than the test holds, each must be refused by its
  // estimate (exit 2), not by an allocation that fails (exit 1) or succeeds and swaps. (Less is
  // not enough for the worker threads' stacks and malloc arenas, which count as address space.)
  AddressSpaceLimit limit(256ull << 20);
  if (!limit.lowered()) GTEST_SKIP() << "cannot lower the address-space limit here";
  const fs::path dir = freshDir("cannot_fit");
  const std::string out = (dir / "x.png").string();
  struct Case {
    std::vector<std::string> args;
    std::string what;
  };
  const Case cases[] = {
      {{"solve", "cornell", "--method", "patch", "--patches", "1000000000"}, "patches, which need"},
      {{"solve", "cornell", "--method", "patch", "--patch-size", "0.001"}, "patches, which need"},
      {{"render", "cornell", "--width", "32768", "--height", "32768", "-o", out},
       "32768 x 32768 pixels need"},
      {tinyRender(
           {"-o", out, "--stats", (dir / "s.json").string(), "--object-points", "2000000000"}),
       "2000000000 points on each of"},
      {{"solve", "cornell", "--method", "voxel", "--voxel-size", "0.1"}, "voxels, which need"},
  };
  for (const Case& c : cases) {
    const CliResult r = run(c.args);
    EXPECT_EQ(r.status, 2) << c.args[3] << ": " << r.err;
    EXPECT_TRUE(has(r.err, c.what) && has(r.err, "GB is available")) << r.err;
  }
  EXPECT_FALSE(fs::exists(out));
}

TEST(BadSettings, NonFiniteNumbersAreRefused) {
  // Before: --exposure nan passed CLI11's range check (every comparison with NaN is false) and
  // gave a black image with exit 0.
  for (const char* bad : {"nan", "inf", "-inf", "100"}) {
    const CliResult r = run(tinyRender({"--exposure", bad}));
    EXPECT_EQ(r.status, 2) << bad << ": " << r.err;
    EXPECT_TRUE(has(r.err, "--exposure")) << r.err;
  }
  const CliResult r = run(tinyRender({"--probe-spacing", "nan"}));
  EXPECT_EQ(r.status, 2) << r.err;
}

TEST(BadSettings, MoreThreadsThanCoresAreClampedWithAWarning) {
  const fs::path dir = freshDir("threads");
  std::vector<std::string> args = {"--threads", "100000"};
  for (const std::string& a : tinyRender({"-o", (dir / "x.png").string()})) args.push_back(a);
  const CliResult r = run(args);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(has(r.err, "--threads 100000 is more than the")) << r.err;
}

}  // namespace
}  // namespace rad::test

namespace rad::test {
namespace {

// The cache directory stays under --cache-max-mb: a run removes its least recently used files
// (here three old 600 KB tables of other scenes) before it adds its own.
TEST(CacheCap, ARunKeepsTheCacheUnderItsCap) {
  const fs::path dir = freshDir("cache_cap");
  const fs::path cache = dir / "cache";
  fs::create_directories(cache);
  const auto old = fs::file_time_type::clock::now() - std::chrono::hours(1);
  for (const char* name : {"masterff-1.bin", "masterff-2.bin", "masterff-3.bin"}) {
    std::ofstream(cache / name) << std::string(600 << 10, 'x');
    fs::last_write_time(cache / name, old);
  }
  fs::last_write_time(cache / "masterff-3.bin", old + std::chrono::minutes(30));
  const CliResult r = run({"solve", "cornell", "--method", "patch", "--patches", "100",
                           "--cache-dir", cache.string(), "--cache-max-mb", "1"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(fs::exists(cache / "masterff-1.bin"));
  EXPECT_FALSE(fs::exists(cache / "masterff-2.bin"));
  EXPECT_TRUE(fs::exists(cache / "masterff-3.bin"));  // the most recently used of them
  EXPECT_EQ(run({"solve", "cornell", "--cache-max-mb", "0"}).status, 2);
}

}  // namespace
}  // namespace rad::test
