// `radiosity animate`: numbered, whole frames of the light animation, relit between frames; a
// video by ffmpeg; bad patterns and a missing ffmpeg refused before any work; an interrupted run
// leaves only whole frames.
#include <fcntl.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <radiosity/image.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <thread>

#include "cli/cli_run.h"

extern char** environ;

namespace rad {
namespace {

namespace fs = std::filesystem;
using test::freshDir;
using test::run;

// The Cornell box with a spot that turns a quarter turn a second about the vertical.
fs::path spinningSpotScene(const fs::path& dir) {
  const std::string obj = std::string(RADIOSITY_TEST_DATA_DIR) + "/scene/cornell/cornell_box.obj";
  return test::writeFile(dir / "spin.json", R"({"geometry": [{"file": ")" + obj + R"("}],
    "lights": [{"type": "spot", "position": [278, 450, 279.5], "direction": [0.7, -0.7, 0],
      "intensity": [2e5, 1.5e5, 1e5], "inner_angle_deg": 15, "outer_angle_deg": 25,
      "spin_deg_per_s": [0, 90, 0]}],
    "camera": {"eye": [278, 273, -800], "target": [278, 273, 0], "fov_deg": 39}})");
}

// Small and quick: the frames' content is the relighter's and the renderer's, tested elsewhere.
std::vector<std::string> animateArgs(const fs::path& scene, const std::string& output) {
  return {"animate",     scene.string(), "-o",      output, "--patches", "300",
          "--cache-dir", "none",         "--width", "24",   "--spp",     "1"};
}

std::vector<std::string> filesIn(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(Animate, WritesNumberedWholeFramesAndTheirTimings) {
  const fs::path dir = freshDir("animate_frames");
  const fs::path scene = spinningSpotScene(dir);
  std::vector<std::string> args = animateArgs(scene, (dir / "out/f_%03d.pfm").string());
  for (const std::string a : {"--frames", "4", "--fps", "2", "--stats"}) args.push_back(a);
  args.push_back((dir / "stats.json").string());
  const test::CliResult r = run(args);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(filesIn(dir / "out"),
            (std::vector<std::string>{"f_000.pfm", "f_001.pfm", "f_002.pfm", "f_003.pfm"}));
  std::vector<double> means;
  for (int f = 0; f < 4; ++f) {
    const Image image = readImage((dir / "out" / fmt::format("f_{:03d}.pfm", f)).string());
    EXPECT_EQ(image.width, 24);
    double sum = 0.0;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) sum += luminance(image.at(x, y));
    means.push_back(sum);
  }
  // The spot turns between frames (45 degrees at 2 fps): the pictures differ.
  EXPECT_GT(std::abs(means[1] - means[0]), 1e-3 * means[0]);
  const nlohmann::json stats = test::readJson((dir / "stats.json").string());
  ASSERT_EQ(stats["patch"]["frames"].size(), 4u);
  EXPECT_DOUBLE_EQ(stats["patch"]["frames"][3]["t"].get<double>(), 1.5);
  EXPECT_GT(stats["patch"]["frames"][1]["relight_ms"].get<double>(), 0.0);
  EXPECT_NE(r.err.find("ms per relight"), std::string::npos) << r.err;
}

TEST(Animate, BadPatternsAndAMissingFfmpegAreRefusedBeforeAnyWork) {
  const fs::path dir = freshDir("animate_refused");
  const fs::path scene = spinningSpotScene(dir);
  for (const std::string pattern :
       {"f.png", "f_%d_%d.png", "f_%4d.png", "f_%04x.png", "f_%04d.gif"}) {
    const test::CliResult r = run(animateArgs(scene, (dir / pattern).string()));
    EXPECT_EQ(r.status, 2) << pattern;
    EXPECT_NE(r.err.find("-o"), std::string::npos) << r.err;
  }
  const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
  ::setenv("PATH", (dir / "nothing_here").c_str(), 1);
  std::vector<std::string> args = animateArgs(scene, (dir / "f_%04d.png").string());
  args.insert(args.end(), {"--video", (dir / "a.mp4").string()});
  const test::CliResult r = run(args);
  ::setenv("PATH", path.c_str(), 1);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("ffmpeg is not installed"), std::string::npos) << r.err;
  EXPECT_EQ(filesIn(dir), std::vector<std::string>{"spin.json"});  // no frame, no video
}

bool onPath(const std::string& program) {
  return std::system(("command -v " + program + " >/dev/null 2>&1").c_str()) == 0;
}

TEST(Animate, EncodesTheFramesIntoAVideo) {
  if (!onPath("ffmpeg"))
    GTEST_SKIP() << "ffmpeg is not installed (scripts/install-deps installs it)";
  const fs::path dir = freshDir("animate_video");
  const fs::path scene = spinningSpotScene(dir);
  std::vector<std::string> args = animateArgs(scene, (dir / "f_%04d.png").string());
  args.insert(args.end(), {"--frames", "3", "--video", (dir / "a.mp4").string()});
  const test::CliResult r = run(args);
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string video = test::readBytes((dir / "a.mp4").string());
  ASSERT_GT(video.size(), 100u);
  EXPECT_EQ(video.substr(4, 4), "ftyp");  // an MP4 (ISO base media) file
  for (const std::string& name : filesIn(dir)) EXPECT_EQ(name.find(".tmp"), std::string::npos);
}

// The binary itself, interrupted as a user would (SIGINT) once its first frame is out: it stops
// with status 130, and every file it leaves is a whole frame (no temporary, no half image).
TEST(Animate, AnInterruptedRunLeavesOnlyWholeFrames) {
  const fs::path dir = freshDir("animate_interrupted");
  const fs::path scene = spinningSpotScene(dir);
  std::vector<std::string> args = {std::string(RADIOSITY_BINARY_DIR) + "/radiosity",
                                   "animate",
                                   scene.string(),
                                   "-o",
                                   (dir / "f_%04d.pfm").string(),
                                   "--patches",
                                   "300",
                                   "--cache-dir",
                                   "none",
                                   "--width",
                                   "160",
                                   "--spp",
                                   "1",
                                   "--frames",
                                   "1000",
                                   "--quiet"};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  ASSERT_EQ(::posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ), 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!fs::exists(dir / "f_0000.pfm") && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ::kill(pid, SIGINT);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  size_t frames = 0;
  for (const std::string& name : filesIn(dir)) {
    if (name == "spin.json") continue;
    ASSERT_EQ(name, fmt::format("f_{:04d}.pfm", frames)) << "a stray or missing file";
    EXPECT_NO_THROW(readImage((dir / name).string())) << name;
    ++frames;
  }
  EXPECT_GE(frames, 1u);
  EXPECT_LT(frames, 1000u);
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

// animate --solution starts from a saved solution instead of solving: its first frame is the
// picture of the solution the file keeps, the one a solving animate starts from.
TEST(Animate, StartsFromASavedSolution) {
  const fs::path dir = freshDir("animate_solution");
  const fs::path scene = spinningSpotScene(dir);
  const std::string rad = (dir / "spin.rad").string();
  const test::CliResult saved = run({"solve", scene.string(), "--method", "patch", "--patches",
                                     "300", "--cache-dir", "none", "--save", rad});
  ASSERT_EQ(saved.status, 0) << saved.err;
  std::vector<std::string> solving = animateArgs(scene, (dir / "a_%d.pfm").string());
  solving.insert(solving.end(), {"--frames", "2"});
  ASSERT_EQ(run(solving).status, 0);
  const test::CliResult loaded =
      run({"animate", scene.string(), "--solution", rad, "-o", (dir / "b_%d.pfm").string(),
           "--cache-dir", "none", "--width", "24", "--spp", "1", "--frames", "2"});
  ASSERT_EQ(loaded.status, 0) << loaded.err;
  EXPECT_EQ(test::readBytes((dir / "a_0.pfm").string()),
            test::readBytes((dir / "b_0.pfm").string()));
  EXPECT_TRUE(fs::exists(dir / "b_1.pfm"));
}

}  // namespace
}  // namespace rad
