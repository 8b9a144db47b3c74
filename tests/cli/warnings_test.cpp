// Warnings: printed as they come and counted at the end of a run; --quiet prints none of them
// (errors only) yet the stats file records them.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <thread>
#include <vector>

#include "cli/cli_run.h"

namespace rad {
namespace {

// A small path-traced render that warns once: more threads than the machine has cores.
std::vector<std::string> warningRender(const test::fs::path& dir) {
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  return {"--threads",
          std::to_string(cores + 1),
          "render",
          "cornell",
          "--width",
          "8",
          "--height",
          "8",
          "--spp",
          "1",
          "--cache-dir",
          "none",
          "-o",
          (dir / "w.png").string(),
          "--stats",
          (dir / "w.json").string(),
          "--object-points",
          "0"};
}

TEST(Warnings, ARunCountsItsWarningsAtTheEnd) {
  const test::fs::path dir = test::freshDir("warnings_counted");
  const test::CliResult r = test::run(warningRender(dir));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("radiosity: warning: --threads"), std::string::npos) << r.err;
  EXPECT_TRUE(r.err.ends_with("radiosity: 1 warning\n")) << r.err;
  const nlohmann::json stats = test::readJson((dir / "w.json").string());
  EXPECT_EQ(stats["warnings"]["count"], 1);
  EXPECT_EQ(stats["warnings"]["messages"].size(), 1u);
}

TEST(Warnings, QuietPrintsNoneButTheStatsRecordThem) {
  const test::fs::path dir = test::freshDir("warnings_quiet");
  std::vector<std::string> args = warningRender(dir);
  args.insert(args.begin(), "--quiet");
  const test::CliResult r = test::run(args);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "");
  const nlohmann::json stats = test::readJson((dir / "w.json").string());
  ASSERT_EQ(stats["warnings"]["count"], 1);
  EXPECT_NE(stats["warnings"]["messages"][0].get<std::string>().find("--threads"),
            std::string::npos)
      << stats["warnings"];
  // Errors still speak.
  const test::CliResult bad = test::run({"--quiet", "render", "no_such_scene.obj"});
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("no_such_scene.obj"), std::string::npos);
}

TEST(Warnings, ARunWithoutWarningsEndsWithoutACount) {
  const test::fs::path dir = test::freshDir("warnings_none");
  const test::CliResult r =
      test::run({"render", "cornell", "--width", "8", "--height", "8", "--spp", "1", "--cache-dir",
                 "none", "-o", (dir / "w.png").string(), "--stats", (dir / "w.json").string(),
                 "--object-points", "0"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find("radiosity: "), std::string::npos) << r.err;  // no warning, no count
  EXPECT_EQ(test::readJson((dir / "w.json").string())["warnings"]["count"], 0);
}

}  // namespace
}  // namespace rad
