// Ctrl-C stops a long computation within about a second in every phase, with status 130 and no
// output written: the binary itself, interrupted as a user would (SIGINT).

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <cstring>
#include <thread>

#include "cli_run.h"

extern char** environ;

namespace rad::test {
namespace {

using Clock = std::chrono::steady_clock;

struct Interrupted {
  int status = -1;       ///< exit status, or -1 if it had to be killed
  double secondsToExit;  ///< from SIGINT to exit
};

// Starts the radiosity binary with `args` (its stderr into `stderrFile` when given, `extraEnv`
// added to its environment); 0 on failure.
pid_t spawnRadiosity(std::vector<std::string> args, const fs::path& stderrFile = {},
                     std::string extraEnv = {}) {
  args.insert(args.begin(), std::string(RADIOSITY_BINARY_DIR) + "/radiosity");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<char*> env;
  for (char** e = environ; *e; ++e) env.push_back(*e);
  if (!extraEnv.empty()) env.push_back(extraEnv.data());
  env.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (!stderrFile.empty())
    posix_spawn_file_actions_addopen(&actions, 2, stderrFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
  pid_t pid = 0;
  const int failed = ::posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), env.data());
  posix_spawn_file_actions_destroy(&actions);
  return failed ? 0 : pid;
}

// Starts radiosity with `args`, sends SIGINT after `after` seconds, and waits up to 20 s for it
// to exit (then kills it, so that a regression fails the test instead of hanging the suite).
Interrupted interruptAfter(const std::vector<std::string>& args, double after,
                           const fs::path& stderrFile = {}) {
  const pid_t pid = spawnRadiosity(args, stderrFile);
  if (pid == 0) return {};
  std::this_thread::sleep_for(std::chrono::duration<double>(after));
  ::kill(pid, SIGINT);
  const auto sent = Clock::now();
  int status = 0;
  while (::waitpid(pid, &status, WNOHANG) == 0) {
    if (Clock::now() - sent > std::chrono::seconds(20)) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      return {-1, 20.0};
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - sent).count();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, seconds};
}

// Before: the path tracer asked whether to stop once per 16x16 tile, so an 8x8 picture at a
// million samples a pixel ran on for minutes (76 s measured).
TEST(Interrupt, ThePathTracerStopsWithinASecondEvenInOneTile) {
  const fs::path dir = freshDir("interrupt_pathtrace");
  const Interrupted r =
      interruptAfter({"render", "cornell", "--method", "pathtrace", "--width", "8", "--height", "8",
                      "--spp", "1048576", "-o", (dir / "x.png").string(), "--cache-dir",
                      (dir / "cache").string(), "--quiet"},
                     1.0);
  EXPECT_EQ(r.status, 130);
  EXPECT_LT(r.secondsToExit, 1.5);
  EXPECT_FALSE(fs::exists(dir / "x.png"));
}

// Before: the voxel method's first shot (shadow rays toward the emitters, per side) never asked.
TEST(Interrupt, TheVoxelFirstShotStopsWithinASecond) {
  const fs::path dir = freshDir("interrupt_first_shot");
  const Interrupted r = interruptAfter(
      {"solve", "cornell", "--method", "voxel", "--voxels", "2000", "--direct-samples", "1048576",
       "--export", (dir / "x.csv").string(), "--cache-dir", (dir / "cache").string(), "--quiet"},
      1.0);
  EXPECT_EQ(r.status, 130);
  EXPECT_LT(r.secondsToExit, 1.5);
  EXPECT_FALSE(fs::exists(dir / "x.csv"));
}

// The voxel solve keeps a checkpoint after every iteration: killed with kill -9 after its second
// iteration and run again, it goes on from there and exports the same file as a run that was
// never interrupted, byte for byte.
TEST(Interrupt, AVoxelSolveKilledAfterTwoIterationsGoesOnToTheSameAnswer) {
  const fs::path dir = freshDir("interrupt_kill9");
  auto solve = [&](const std::string& cache, const std::string& csv) {
    return std::vector<std::string>{std::string(RADIOSITY_BINARY_DIR) + "/radiosity",
                                    "solve",
                                    "cornell",
                                    "--method",
                                    "voxel",
                                    "--voxels",
                                    "50000",
                                    "--sphere-radius",
                                    "20",
                                    "--iterations",
                                    "4",
                                    "--cache-dir",
                                    (dir / cache).string(),
                                    "--export",
                                    (dir / csv).string(),
                                    "--quiet"};
  };
  auto runToEnd = [](std::vector<std::string> args) {
    args.erase(args.begin());
    return run(args);
  };
  ASSERT_EQ(runToEnd(solve("whole", "whole.csv")).status, 0);

  // Started, then killed once its checkpoint says two iterations are done.
  std::vector<std::string> args = solve("cache", "resumed.csv");
  args.erase(args.begin());
  const pid_t pid = spawnRadiosity(args);
  ASSERT_NE(pid, 0);
  auto iterationsInCheckpoint = [&]() -> int {
    std::error_code ec;
    for (fs::directory_iterator it(dir / "cache", ec), end; !ec && it != end; it.increment(ec)) {
      if (it->path().extension() != ".checkpoint") continue;
      const std::string bytes = readBytes(it->path().string());
      int32_t done = 0;
      if (bytes.size() >= 16) std::memcpy(&done, bytes.data() + 12, 4);
      return done;
    }
    return -1;
  };
  const auto deadline = Clock::now() + std::chrono::seconds(60);
  while (iterationsInCheckpoint() < 2 && Clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ::kill(pid, SIGKILL);
  ::waitpid(pid, nullptr, 0);
  ASSERT_EQ(iterationsInCheckpoint(), 2) << "the solve ended before it could be killed";
  EXPECT_FALSE(fs::exists(dir / "resumed.csv"));

  const CliResult resumed = runToEnd(solve("cache", "resumed.csv"));
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  EXPECT_EQ(readBytes((dir / "resumed.csv").string()), readBytes((dir / "whole.csv").string()));
  EXPECT_EQ(iterationsInCheckpoint(), -1) << "the checkpoint outlived its solve";
}

// A file in `dir` whose name starts with `prefix`, or "" (a checkpoint or cache the run wrote).
fs::path fileStartingWith(const fs::path& dir, const std::string& prefix) {
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (it->path().filename().string().rfind(prefix, 0) == 0) return it->path();
  return {};
}

// Runs `args` with checkpoints every 0.2 s, kills it (kill -9) once `prefix`'s file is in the
// cache folder `cache`, and returns whether it was still running then.
bool killOnceCheckpointed(const std::vector<std::string>& args, const fs::path& cache,
                          const std::string& prefix) {
  const pid_t pid = spawnRadiosity(args, {}, "RADIOSITY_CHECKPOINT_SECONDS=0.2");
  if (pid == 0) return false;
  const auto deadline = Clock::now() + std::chrono::seconds(60);
  while (fileStartingWith(cache, prefix).empty() && Clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const bool running = ::waitpid(pid, nullptr, WNOHANG) == 0;
  ::kill(pid, SIGKILL);
  ::waitpid(pid, nullptr, 0);
  return running;
}

// The path tracer keeps its finished tiles as it goes: killed part way and run again, it renders
// only the rest, and the picture is the uninterrupted one, byte for byte.
TEST(Interrupt, APathTracedRenderKilledPartWayGoesOnToTheSamePicture) {
  const fs::path dir = freshDir("interrupt_kill_pathtrace");
  auto render = [&](const std::string& cache, const std::string& out) {
    return std::vector<std::string>{"render",      "cornell",
                                    "--method",    "pathtrace",
                                    "--width",     "96",
                                    "--height",    "96",
                                    "--spp",       "512",
                                    "--cache-dir", (dir / cache).string(),
                                    "-o",          (dir / out).string()};
  };
  ASSERT_EQ(run(render("none", "whole.pfm")).status, 0);
  ASSERT_TRUE(killOnceCheckpointed(render("cache", "resumed.pfm"), dir / "cache", "pathtrace-"));
  const CliResult r = run(render("cache", "resumed.pfm"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("went on from a checkpoint"), std::string::npos) << r.err;
  EXPECT_EQ(readBytes((dir / "resumed.pfm").string()), readBytes((dir / "whole.pfm").string()));
  EXPECT_TRUE(fileStartingWith(dir / "cache", "pathtrace-").empty());
}

// The patch method keeps the form-factor rows it casts as it goes: killed part way and run
// again, it casts only the rest, and the solution is the uninterrupted one, byte for byte.
TEST(Interrupt, APatchSolveKilledWhileCastingGoesOnToTheSameAnswer) {
  const fs::path dir = freshDir("interrupt_kill_patch");
  auto solve = [&](const std::string& cache, const std::string& out) {
    return std::vector<std::string>{"solve",       "cornell",
                                    "--method",    "patch",
                                    "--patches",   "12000",
                                    "--ff-rays",   "512",
                                    "--cache-dir", (dir / cache).string(),
                                    "--export",    (dir / out).string(),
                                    "--stats",     (dir / (out + ".json")).string()};
  };
  ASSERT_EQ(run(solve("none", "whole.csv")).status, 0);
  ASSERT_TRUE(killOnceCheckpointed(solve("cache", "resumed.csv"), dir / "cache", "masterff-"));
  ASSERT_EQ(run(solve("cache", "resumed.csv")).status, 0);
  const nlohmann::json stats = readJson((dir / "resumed.csv.json").string())["patch"];
  EXPECT_GT(stats["rows_reused"].get<int>(), 0);    // kept before the kill
  EXPECT_GT(stats["rows_computed"].get<int>(), 0);  // the kill came before the last row
  EXPECT_EQ(readBytes((dir / "resumed.csv").string()), readBytes((dir / "whole.csv").string()));
}

TEST(Interrupt, CtrlCDuringTheSweepsSaysHowToGoOn) {
  const fs::path dir = freshDir("interrupt_sweeps");
  const Interrupted r =
      interruptAfter({"solve", "cornell", "--method", "voxel", "--voxels", "50000",
                      "--sphere-radius", "38", "--iterations", "6", "--cache-dir",
                      (dir / "cache").string(), "--export", (dir / "x.csv").string()},
                     2.5, dir / "err.txt");
  EXPECT_EQ(r.status, 130);
  const std::string err = readBytes((dir / "err.txt").string());
  EXPECT_NE(err.find("interrupted; no output written; the solve goes on from iteration"),
            std::string::npos)
      << err;
  EXPECT_FALSE(fs::exists(dir / "x.csv"));
}

// Without a terminal (a batch job, CI), a long run prints a progress line every 5 s to stderr
// instead of a bar; before, it printed nothing for minutes.
TEST(Interrupt, ALongRunWithoutATerminalPrintsProgressLines) {
  const fs::path dir = freshDir("progress_lines");
  const Interrupted r = interruptAfter(
      {"render", "cornell", "--method", "pathtrace", "--width", "64", "--height", "64", "--spp",
       "1048576", "-o", (dir / "x.png").string(), "--cache-dir", "none"},
      5.8, dir / "err.txt");
  EXPECT_EQ(r.status, 130);
  const std::string err = readBytes((dir / "err.txt").string());
  EXPECT_NE(err.find("render: "), std::string::npos) << err;
  EXPECT_NE(err.find("% done, 5 s"), std::string::npos) << err;
  EXPECT_EQ(err.find('\r'), std::string::npos) << "a terminal's bar in a log";
}

}  // namespace
}  // namespace rad::test
