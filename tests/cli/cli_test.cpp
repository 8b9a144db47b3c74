// End-to-end tests of the command line, driven in-process through runCli.
#include "cli.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <radiosity/image.h>
#include <radiosity/solver_settings.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <tuple>

#include "cli/cli_run.h"
#include "core/address_space_limit.h"

namespace fs = std::filesystem;
using rad::test::CliResult;
using rad::test::freshDir;
using rad::test::readBytes;
using rad::test::readJson;
using rad::test::run;
using rad::test::writeFile;

namespace {

// The data rows of an exported CSV, after checking its header: the documented columns
// (docs/ARCHITECTURE.md), one row per voxel side or patch.
size_t csvRowCount(const std::string& path) {
  std::ifstream rows(path);
  std::string header, line;
  std::getline(rows, header);
  EXPECT_EQ(
      header,
      "id,object,area,cx,cy,cz,nx,ny,nz,E_r,E_g,E_b,rho_r,rho_g,rho_b,H_r,H_g,H_b,B_r,B_g,B_b");
  size_t count = 0;
  while (std::getline(rows, line)) ++count;
  return count;
}

// Mean of the pixels' RGB radiance.
double meanRadiance(const rad::Image& image) {
  double sum = 0.0;
  for (const rad::Color& c : image.pixels) sum += double(c.r) + double(c.g) + double(c.b);
  return sum / (3.0 * double(image.pixels.size()));
}

// How many different RGB values the pixels hold.
size_t distinctPixels(const rad::Image& image) {
  std::set<std::tuple<float, float, float>> values;
  for (const rad::Color& c : image.pixels) values.insert({c.r, c.g, c.b});
  return values.size();
}

TEST(Cli, RendersCornellBoxWithStats) {
  const fs::path dir = freshDir("render");
  const std::string png = (dir / "x.png").string(), stats = (dir / "s.json").string();
  const CliResult r =
      run({"render", "cornell", "--method", "pathtrace", "--width", "64", "--height", "64", "--spp",
           "4", "-o", png, "--stats", stats, "--object-points", "8"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_GT(fs::file_size(png), 100u);
  const nlohmann::json j = readJson(stats);
  // The fields of the stats contract (docs/ARCHITECTURE.md, "Stats JSON").
  for (const char* key : {"scene", "method", "counts", "timings_s", "iterations", "residual",
                          "energy", "objects", "memory_peak_bytes"})
    EXPECT_TRUE(j.contains(key)) << key;
  for (const char* key : {"triangles", "patches", "voxels", "directions", "rays"})
    EXPECT_TRUE(j["counts"].contains(key)) << key;
  for (const char* key : {"load", "prepare", "solve", "render", "total"})
    EXPECT_TRUE(j["timings_s"].contains(key)) << key;
  EXPECT_EQ(j["scene"], "cornell");
  EXPECT_EQ(j["method"], "pathtrace");
  EXPECT_GT(j["counts"]["rays"].get<double>(), 64.0 * 64 * 4);
  EXPECT_GT(j["memory_peak_bytes"].get<double>(), 1e6);
  // One entry per object of the Cornell box, with physically sensible numbers: the floor is
  // lit (irradiance > 0) and white paint reflects less than it receives.
  ASSERT_EQ(j["objects"].size(), 8u);
  for (const auto& o : j["objects"]) {
    EXPECT_GT(o["area"].get<double>(), 0.0);
    if (o["name"] == "floor") {
      EXPECT_GT(o["mean_irradiance"][1].get<double>(), 0.0);
      EXPECT_LT(o["mean_radiosity"][1].get<double>(), o["mean_irradiance"][1].get<double>());
    }
  }
  // Absorbed power cannot exceed what was emitted (the box is open, light escapes).
  EXPECT_LT(j["energy"]["absorbed"][1].get<double>(), j["energy"]["emitted"][1].get<double>());
  EXPECT_GT(j["energy"]["absorbed"][1].get<double>(),
            0.3 * j["energy"]["emitted"][1].get<double>());
}

TEST(Cli, WritesExrAndPfm) {
  const fs::path dir = freshDir("formats");
  for (const char* name : {"a.exr", "a.pfm"}) {
    const std::string path = (dir / name).string();
    const CliResult r = run({"render", "cornell", "--width", "16", "--height", "16", "--spp", "1",
                             "-o", path, "--quiet"});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::exists(path)) << path;
    EXPECT_TRUE(r.err.empty()) << r.err;
  }
}

TEST(Cli, ASizeGivenAloneKeepsTheCamerasAspectRatio) {
  // The Cornell camera is 512 x 512: a width alone gave 40 x 512 before.
  const std::string pfm = (freshDir("aspect") / "a.pfm").string();
  struct Case {
    std::vector<std::string> size;
    int width, height;
  };
  for (const Case& c : {Case{{"--width", "40"}, 40, 40}, Case{{"--height", "24"}, 24, 24},
                        Case{{"--width", "40", "--height", "10"}, 40, 10}}) {
    std::vector<std::string> args{"render", "cornell", "--spp", "1", "-o", pfm};
    args.insert(args.end(), c.size.begin(), c.size.end());
    const CliResult r = run(args);
    ASSERT_EQ(r.status, 0) << r.err;
    const rad::Image image = rad::readImage(pfm);
    EXPECT_EQ(image.width, c.width) << c.size[0];
    EXPECT_EQ(image.height, c.height) << c.size[0];
  }
}

TEST(Cli, OutOfMemoryIsAClearErrorAndWritesNothing) {
  // 10^8 patches need gigabytes; with 32 MB of address space left (ulimit -v) the run must say
  // so and write nothing, not end on a bare std::bad_alloc.
#ifdef __SANITIZE_ADDRESS__
  GTEST_SKIP() << "AddressSanitizer's own allocator needs more than the 32 MB left";
#endif
  const fs::path dir = freshDir("memory");
  const std::string stats = (dir / "s.json").string(), csv = (dir / "p.csv").string();
  CliResult r;
  {
    const rad::test::AddressSpaceLimit limit(32u << 20);
    if (limit.alreadyBelow()) GTEST_SKIP() << "the address space is already limited below 32 MB";
    ASSERT_TRUE(limit.lowered());
    r = run({"solve", "cornell", "--method", "patch", "--patches", "100000000", "--stats", stats,
             "--export", csv, "--quiet"});
  }
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("out of memory"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(stats));
  EXPECT_FALSE(fs::exists(csv));
}

TEST(Cli, UnsupportedOutputExtensionFailsBeforeRendering) {
  const fs::path dir = freshDir("badext");
  const std::string jpg = (dir / "x.jpg").string();
  const CliResult r = run({"render", "cornell", "-o", jpg});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("x.jpg"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(".png"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(jpg));
}

// Two outputs of one run on one file: the second would overwrite the first. Refused before any
// work, naming both options; nothing written.
TEST(Cli, TwoOutputsOnOneFileAreRefused) {
  const fs::path dir = freshDir("same_output");
  const std::string same = (dir / "same.csv").string();
  const CliResult r = run({"solve", "cornell", "--method", "voxel", "--voxels", "2000", "--export",
                           same, "--stats", (dir / "." / "same.csv").string()});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--stats"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--export"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(same));
}

// A disk that fills up while an output is written (/dev/full refuses every write): the run ends
// with exit 2 and the message, as for a bad output path.
TEST(Cli, AFullDiskIsAnOutputErrorWithExitTwo) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full here";
  const CliResult full = run({"solve", "cornell", "--method", "voxel", "--voxels", "2000",
                              "--sphere-radius", "4", "--stats", "/dev/full"});
  EXPECT_EQ(full.status, 2) << full.err;
  EXPECT_NE(full.err.find("/dev/full"), std::string::npos) << full.err;
}

TEST(Cli, MissingSceneFileIsBadInput) {
  const fs::path dir = freshDir("missing");
  const std::string png = (dir / "x.png").string();
  const CliResult r = run({"render", (dir / "nope.obj").string(), "-o", png});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("nope.obj"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
  EXPECT_FALSE(fs::exists(png));
}

TEST(Cli, SceneWithoutLightIsRejected) {
  const fs::path dir = freshDir("dark");
  const fs::path obj = writeFile(dir / "dark.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string png = (dir / "x.png").string();
  const CliResult r = run({"render", obj.string(), "-o", png});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("black"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(png));
}

TEST(Cli, UsageErrorsExitTwo) {
  EXPECT_EQ(run({}).status, 2);
  EXPECT_EQ(run({"render"}).status, 2);
  EXPECT_EQ(run({"render", "cornell", "--spp", "zero"}).status, 2);
  EXPECT_EQ(run({"render", "cornell", "--method", "magic"}).status, 2);
  EXPECT_EQ(run({"frobnicate"}).status, 2);
  EXPECT_EQ(run({"--help"}).status, 0);
}

TEST(Cli, NumbersOutOfRangeSayWhatWasExpected) {
  // The option, the value and what it should have been; before, CLI11's own checks printed the
  // range up to the largest double (309 digits).
  const CliResult size = run({"solve", "cornell", "--method", "voxel", "--voxel-size", "0"});
  EXPECT_EQ(size.status, 2);
  EXPECT_NE(size.err.find("--voxel-size: 0 out of range (0, inf)"), std::string::npos) << size.err;
  EXPECT_LT(size.err.size(), 200u) << size.err;
  const CliResult tolerance = run({"solve", "cornell", "--tolerance", "-0.5"});
  EXPECT_EQ(tolerance.status, 2);
  EXPECT_NE(tolerance.err.find("--tolerance: -0.5 out of range [0, inf)"), std::string::npos)
      << tolerance.err;
  const CliResult patch = run({"solve", "cornell", "--patch-size", "x"});
  EXPECT_EQ(patch.status, 2);
  EXPECT_NE(patch.err.find("'x' is not a number"), std::string::npos) << patch.err;
}

TEST(Cli, InfoPrintsCountsAndPower) {
  const CliResult r = run({"info", "cornell"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("objects    8"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("lights     0"), std::string::npos) << r.out;
  // In millimetres: Ke per square millimetre, so pi Ke A of the 130 x 105 mm light is watts, and
  // the area in square metres too.
  EXPECT_NE(r.out.find("unit       mm (0.001 m)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(") W (Ke taken per mm^2)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" mm^2 ("), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" m^2)"), std::string::npos) << r.out;
  // An OBJ alone does not say its unit.
  const CliResult obj =
      run({"info", std::string(RADIOSITY_TEST_DATA_DIR) + "/scene/small/small.obj"});
  ASSERT_EQ(obj.status, 0) << obj.err;
  EXPECT_NE(obj.out.find("unit       unknown"), std::string::npos) << obj.out;
  EXPECT_NE(obj.out.find("Ke taken per scene unit^2"), std::string::npos) << obj.out;
  // A textured scene names its textures and their size.
  const CliResult office = run({"info", std::string(RADIOSITY_SOURCE_DIR) + "/scenes/office.json"});
  ASSERT_EQ(office.status, 0) << office.err;
  EXPECT_NE(office.out.find("1 textured"), std::string::npos) << office.out;
  EXPECT_NE(office.out.find("tiles.png (128 x 128 texels)"), std::string::npos) << office.out;
}

// A directional light has no position: info gives its way and its irradiance in the scene's unit.
TEST(Cli, InfoNamesTheSunsWayAndIrradiance) {
  const fs::path dir = freshDir("info_sun");
  const fs::path scene = writeFile(
      dir / "sun.json",
      R"({"unit": "mm", "geometry": [{"file": ")" + std::string(RADIOSITY_TEST_DATA_DIR) +
          R"(/scene/small/small.obj"}], "lights": [{"type": "directional", "direction": [0, -1, 0],
          "irradiance": [0.001, 0.001, 0.001]}]})");
  const CliResult r = run({"info", scene.string()});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("directional along (0, -1, 0), irradiance (0.001, 0.001, 0.001) W/mm^2"),
            std::string::npos)
      << r.out;
}

TEST(Cli, InfoWarnsAboutDarkScene) {
  const fs::path dir = freshDir("info_dark");
  const fs::path obj = writeFile(dir / "dark.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const CliResult r = run({"info", obj.string()});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("no emitting surface"), std::string::npos) << r.out;
}

TEST(Cli, SameSeedSameImage) {
  const fs::path dir = freshDir("seed");
  auto render = [&](const std::string& name, const std::string& seed, const std::string& threads) {
    const std::string path = (dir / name).string();
    EXPECT_EQ(run({"render", "cornell", "--width", "24", "--height", "24", "--spp", "2", "--seed",
                   seed, "--threads", threads, "-o", path, "--quiet"})
                  .status,
              0);
    return readBytes(path);
  };
  const std::string a = render("a.pfm", "7", "1"), b = render("b.pfm", "7", "2");
  const std::string c = render("c.pfm", "8", "2");
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

TEST(Cli, SolvesWithVoxelsAndExports) {
  const fs::path dir = freshDir("voxel_solve");
  const std::string csv = (dir / "v.csv").string(), ply = (dir / "v.ply").string();
  const std::string stats = (dir / "v.json").string();
  const std::vector<std::string> coarse = {"--voxels",         "3000", "--sphere-radius", "4",
                                           "--direct-samples", "4",    "--quiet"};
  std::vector<std::string> args = {"solve",    "cornell", "--method", "voxel",
                                   "--export", csv,       "--stats",  stats};
  args.insert(args.end(), coarse.begin(), coarse.end());
  ASSERT_EQ(run(args).status, 0);
  const nlohmann::json j = readJson(stats);
  EXPECT_EQ(j["method"], "voxel");
  EXPECT_GT(j["counts"]["voxels"].get<int>(), 2000);
  // The digital sphere of radius 4 has 134 directions (python3 brute-force count).
  EXPECT_EQ(j["counts"]["directions"].get<int>(), 134);
  // By default the iterations go on until the light still bouncing is below 1e-3 of the light
  // put in, well within the cap of 100.
  EXPECT_TRUE(j["converged"].get<bool>());
  EXPECT_LT(j["residual"].get<double>(), 1e-3);
  const size_t iterations = j["iterations"].get<size_t>();
  EXPECT_GT(iterations, 6u);
  EXPECT_LT(iterations, 100u);
  EXPECT_EQ(j["residuals"].size(), iterations);
  // Each iteration's sweep time, adding up to no more than the sweeps' total.
  const nlohmann::json& seconds = j["voxel"]["seconds"];
  ASSERT_EQ(seconds["iterations"].size(), iterations);
  double sum = 0.0;
  for (const auto& t : seconds["iterations"]) {
    EXPECT_GT(t.get<double>(), 0.0);
    sum += t.get<double>();
  }
  EXPECT_LE(sum, seconds["sweeps"].get<double>());
  ASSERT_EQ(j["objects"].size(), 8u);
  const size_t count = csvRowCount(csv);
  EXPECT_EQ(count, j["counts"]["voxels"].get<size_t>());

  args[5] = ply;
  ASSERT_EQ(run(args).status, 0);
  std::ifstream plyIn(ply, std::ios::binary);
  std::string magic;
  std::getline(plyIn, magic);
  EXPECT_EQ(magic, "ply");
  EXPECT_GT(fs::file_size(ply), count * 39);  // 6 floats, 3 bytes, 3 floats a vertex

  // --threads bounds the sweeps' threads; they share each direction, so one thread exports the
  // same bytes as all of them.
  std::vector<std::string> oneThread = {"--threads", "1"};
  oneThread.insert(oneThread.end(), args.begin(), args.end());
  const std::string serialCsv = (dir / "serial.csv").string();
  oneThread[7] = serialCsv;
  ASSERT_EQ(run(oneThread).status, 0);
  const nlohmann::json serial = readJson(stats);
  EXPECT_EQ(serial["voxel"]["sweep_threads"].get<int>(), 1);
  EXPECT_GE(j["voxel"]["sweep_threads"].get<int>(), 1);
  EXPECT_EQ(readBytes(serialCsv), readBytes(csv));
  EXPECT_LE(serial["voxel"]["bytes_per_side"].get<double>(),
            j["voxel"]["bytes_per_side"].get<double>());
  // Per voxel (cell) and per side: a cell holds one side or more.
  EXPECT_GE(j["voxel"]["bytes_per_voxel"].get<double>(),
            j["voxel"]["bytes_per_side"].get<double>());

  // The tail estimate (on by default) adds the bounces after the sixth, a little light on every
  // surface; --no-tail-estimate leaves them out.
  EXPECT_GT(j["voxel"]["tail_share"].get<double>(), 0.0);
  args.push_back("--no-tail-estimate");
  ASSERT_EQ(run(args).status, 0);
  const nlohmann::json truncated = readJson(stats);
  EXPECT_EQ(truncated["voxel"]["tail_share"].get<double>(), 0.0);
  for (size_t k = 0; k < j["objects"].size(); ++k) {
    const nlohmann::json &with = j["objects"][k], &without = truncated["objects"][k];
    if (with["name"] == "light") continue;  // its own emission dwarfs the change
    EXPECT_LT(without["mean_radiosity"][0].get<double>(), with["mean_radiosity"][0].get<double>())
        << with["name"];
  }

  // The sweeps after the first on a coarser sphere: R = 3 has 90 directions (python3
  // brute-force count); the stats name both spheres' counts.
  EXPECT_EQ(j["voxel"]["later_directions"].get<int>(), 134);
  args.insert(args.end(), {"--later-sphere-radius", "3"});
  ASSERT_EQ(run(args).status, 0);
  const nlohmann::json coarser = readJson(stats);
  EXPECT_EQ(coarser["counts"]["directions"].get<int>(), 134);
  EXPECT_EQ(coarser["voxel"]["later_directions"].get<int>(), 90);
}

TEST(Cli, BenchVoxelSamplesTheSphereAndCountsMemoryAsASolveDoes) {
  // R = 38 has 14,790 directions, 7,395 pairs: every 500th pair is 15 of them, 30 directions.
  // One thread, so that both runs hold one thread's records (a thread that never ran holds none).
  const CliResult bench = run({"bench", "voxel", "--voxels", "5000", "--pair-stride", "500",
                               "--threads", "1", "--json", "--quiet"});
  ASSERT_EQ(bench.status, 0) << bench.err;
  const nlohmann::json b = nlohmann::json::parse(bench.out)["voxel"];
  EXPECT_EQ(b["directions"].get<int>(), 14790);
  EXPECT_EQ(b["directions_swept"].get<int>(), 30);
  EXPECT_GT(b["visits_per_s"].get<double>(), 0.0);
  // The bytes it reports are a solve's of the same grid: it sweeps fewer directions, but sizes
  // its line records, and the waiting sides' places reserved with them, for the sphere's widest,
  // as the solve does (neither run needs more places than that reservation: 7.7 a line here at
  // most, measured, against 8).
  const fs::path dir = freshDir("bench_voxel");
  const std::string stats = (dir / "solve.json").string();
  ASSERT_EQ(run({"solve", "room:16", "--method", "voxel", "--voxels", "5000", "--iterations", "1",
                 "--no-first-shot", "--threads", "1", "--stats", stats, "--quiet"})
                .status,
            0);
  const nlohmann::json solve = readJson(stats)["voxel"];
  EXPECT_EQ(solve["cells"].get<size_t>(), b["voxels"].get<size_t>());
  EXPECT_NEAR(b["bytes_per_voxel"].get<double>(), solve["bytes_per_voxel"].get<double>(),
              0.001 * solve["bytes_per_voxel"].get<double>());
}

// A solve stopped by its cap above its tolerance says so: a warning with the residual, the
// tolerance and what to change, and "converged": false in the stats.
TEST(Cli, SolveEndedAboveItsToleranceWarnsAndSaysSoInTheStats) {
  const fs::path dir = freshDir("not_converged");
  const std::string stats = (dir / "s.json").string();
  const std::vector<std::vector<std::string>> runs = {
      {"--method", "patch", "--patches", "300", "--ff-rays", "64", "--max-iterations", "3",
       "--cache-dir", "none"},
      {"--method", "voxel", "--voxels", "3000", "--sphere-radius", "4", "--direct-samples", "4",
       "--iterations", "2"}};
  for (const std::vector<std::string>& options : runs) {
    SCOPED_TRACE(options[1]);
    std::vector<std::string> args = {"solve", "cornell", "--stats", stats};
    args.insert(args.end(), options.begin(), options.end());
    const CliResult r = run(args);
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string limit = options[1] == "patch" ? "--max-iterations 3" : "--iterations 2";
    EXPECT_NE(r.err.find("warning: " + options[1] + " solve not converged: "), std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find(limit), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("above --tolerance 0.001"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("(not converged)"), std::string::npos) << r.err;  // the summary line
    const nlohmann::json j = readJson(stats);
    EXPECT_FALSE(j["converged"].get<bool>());
    EXPECT_GT(j["residual"].get<double>(), 1e-3);
  }
}

TEST(Cli, RendersWithVoxels) {
  const fs::path dir = freshDir("voxel_render");
  const std::string png = (dir / "v.png").string();
  const CliResult r = run({"render", "cornell", "--method", "voxel", "--voxels", "3000",
                           "--sphere-radius", "4", "--width", "32", "--height", "32", "-o", png});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(png));
}

TEST(Cli, SolvesWithPatchesExportsAndCaches) {
  const fs::path dir = freshDir("patch_solve");
  const std::string csv = (dir / "p.csv").string(), stats = (dir / "p.json").string();
  const std::vector<std::string> args = {
      "solve",    "cornell",   "--method", "patch",       "--patches",
      "500",      "--ff-rays", "64",       "--cache-dir", (dir / "cache").string(),
      "--export", csv,         "--stats",  stats};
  const CliResult first = run(args);
  ASSERT_EQ(first.status, 0) << first.err;
  const nlohmann::json j = readJson(stats);
  EXPECT_EQ(j["method"], "patch");
  EXPECT_GE(j["counts"]["patches"].get<int>(), 500);
  // 64 hemisphere rays a patch, plus one visibility ray per quadrature point (16) for each pair
  // of a patch and a light patch facing it, the light's columns being exact.
  const double patches = j["counts"]["patches"].get<double>(),
               rays = j["counts"]["rays"].get<double>();
  const double exactColumns = j["patch"]["exact_columns"].get<double>();
  EXPECT_GE(exactColumns, 1.0);
  EXPECT_GT(rays, 64.0 * patches);
  EXPECT_LE(rays, 64.0 * patches + 16.0 * patches * exactColumns);
  EXPECT_GE(j["iterations"].get<int>(), 1);
  EXPECT_LT(j["residual"].get<double>(), 1e-3);  // the default tolerance
  EXPECT_TRUE(j["converged"].get<bool>());
  EXPECT_EQ(j["patch"]["row_sum"]["scaled_for_reflection"].get<int>(), 0);
  ASSERT_EQ(j["objects"].size(), 8u);
  EXPECT_EQ(csvRowCount(csv), j["counts"]["patches"].get<size_t>());
  // The second run loads the form factors from the cache.
  const CliResult second = run(args);
  ASSERT_EQ(second.status, 0) << second.err;
  // The summary line (info, on stderr) says where the form factors came from.
  EXPECT_NE(second.err.find("form factors loaded"), std::string::npos) << second.err;
}

// The three solvers solve one system (one cached table: without a cache, progressive
// refinement casts its own rows, which are not made reciprocal), so their images agree.
TEST(Cli, PatchSolversGiveTheSameImage) {
  const fs::path dir = freshDir("patch_solvers");
  auto render = [&](const std::string& solver) {
    const std::string pfm = (dir / (solver + ".pfm")).string();
    const std::string stats = (dir / (solver + ".json")).string();
    const CliResult r =
        run({"render",   "cornell",   "--method",    "patch",       "--patches",
             "300",      "--ff-rays", "64",          "--cache-dir", (dir / "cache").string(),
             "--solver", solver,      "--tolerance", "1e-6",        "--width",
             "32",       "--height",  "32",          "-o",          pfm,
             "--stats",  stats,       "--quiet"});
    EXPECT_EQ(r.status, 0) << r.err;
    const nlohmann::json j = readJson(stats);
    EXPECT_EQ(j["patch"]["solver"], solver);
    EXPECT_LT(j["residual"].get<double>(), 1e-6);
    return meanRadiance(rad::readImage(pfm));
  };
  const double gaussSeidel = render("gauss-seidel");
  ASSERT_GT(gaussSeidel, 0.0);
  // Each solver stops at a relative residual ||r||_A < 1e-6 of the emitted power ||E||_A; with a
  // reciprocal table and rho <= 0.78 (the Cornell light's; the walls' are lower) its error in B
  // is at most ||r||_A / (1 - 0.78) < 5e-6 ||E||_A, so two solutions differ by < 1e-5 ||E||_A. The
  // image weighs the surfaces by their projected, not their true, area, and B >= E; 1e-4 of its
  // mean leaves an order of magnitude for that (measured: 2e-7).
  EXPECT_NEAR(render("jacobi"), gaussSeidel, 1e-4 * gaussSeidel);
  EXPECT_NEAR(render("progressive"), gaussSeidel, 1e-4 * gaussSeidel);
}

// Flat shading gives each patch one radiance, so with one camera ray per pixel the image holds
// at most one value per patch (and black where the rays leave the box); smooth shading
// interpolates across patches, so nearly every pixel differs.
TEST(Cli, FlatShadingIsConstantPerPatch) {
  const fs::path dir = freshDir("patch_shading");
  const std::string stats = (dir / "s.json").string();
  auto render = [&](const std::string& shading) {
    const std::string pfm = (dir / (shading + ".pfm")).string();
    const CliResult r =
        run({"render",    "cornell",   "--method", "patch",       "--patches",
             "300",       "--ff-rays", "16",       "--cache-dir", (dir / "cache").string(),
             "--shading", shading,     "--direct", "solution",    "--spp",
             "1",         "--width",   "64",       "--height",    "64",
             "-o",        pfm,         "--stats",  stats,         "--quiet"});
    EXPECT_EQ(r.status, 0) << r.err;
    return rad::readImage(pfm);
  };
  const rad::Image flat = render("flat");
  const size_t patches = readJson(stats)["counts"]["patches"].get<size_t>();
  const rad::Image smooth = render("smooth");
  EXPECT_LE(distinctPixels(flat), patches + 1);
  // 64 x 64 = 4096 pixels, about 300 patches: smooth must exceed the flat bound by far.
  EXPECT_GT(distinctPixels(smooth), 2 * (patches + 1));
}

// Per-pixel direct light is the default for radiosity pictures; a voxel solution without its first
// shot keeps no direct light apart, which the command says instead of adding it twice.
TEST(Cli, PerPixelDirectLightNeedsItKeptApart) {
  const fs::path dir = freshDir("per_pixel_direct");
  const std::string out = (dir / "v.pfm").string();
  const CliResult r =
      run({"render", "cornell", "--method", "voxel", "--voxels", "3000", "--sphere-radius", "4",
           "--iterations", "2", "--no-first-shot", "--width", "16", "--height", "16", "-o", out});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("--direct per-pixel"), std::string::npos) << r.err;
  const CliResult quiet =
      run({"render", "cornell", "--method", "voxel", "--voxels", "3000", "--sphere-radius", "4",
           "--iterations", "2", "--no-first-shot", "--direct", "solution", "--width", "16",
           "--height", "16", "-o", out});
  EXPECT_EQ(quiet.err.find("--direct per-pixel"), std::string::npos) << quiet.err;
  EXPECT_EQ(run({"render", "cornell", "--direct", "sometimes", "-o", out}).status, 2);
}

// The scene's "solver" keys choose the same settings as the flags; a bad value names its key.
TEST(Cli, SceneSolverKeysChooseSettings) {
  const fs::path dir = freshDir("patch_scene_keys");
  const fs::path obj =
      writeFile(dir / "room.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  auto scene = [&](const std::string& solver) {
    return writeFile(dir / "s.json", R"({"geometry": [{"file": "room.obj"}],
      "materials": {"default": {"rho": [0.5, 0.5, 0.5], "emission": [1, 1, 1]}},
      "solver": )" + solver + "}")
        .string();
  };
  const std::string stats = (dir / "s.stats.json").string();
  CliResult r =
      run({"solve", scene(R"({"method": "patch", "patch_size": 0.25, "solver": "progressive",
            "cache_dir": "none", "ff_rays": 16, "max_iterations": 50, "shading": "flat"})"),
           "--stats", stats, "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = readJson(stats);
  EXPECT_EQ(j["counts"]["patches"].get<int>(), 16);
  EXPECT_EQ(j["patch"]["solver"], "progressive");
  r = run({"solve", scene(R"({"method": "patch", "solver": "bogus"})")});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("/solver/solver"), std::string::npos) << r.err;

  // The voxel keys, and a flag that wins over its key, on two glowing squares facing each other
  // (light goes back and forth: a tail to estimate). Digital spheres of R = 4, 3, 2 have 134, 90
  // and 26 directions (python3 brute-force counts).
  writeFile(dir / "room.obj",
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\n"
            "v 0 1 1\nf 1 2 3 4\nf 8 7 6 5\n");
  const std::string voxel = scene(R"({"method": "voxel", "voxels": 500, "sphere_radius": 4,
      "later_sphere_radius": 3, "iterations": 3, "first_shot": false, "normalize": true,
      "jitter_lines": false, "tail_estimate": false})");
  r = run({"solve", voxel, "--stats", stats, "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  nlohmann::json v = readJson(stats);
  EXPECT_EQ(v["counts"]["directions"].get<int>(), 134);
  EXPECT_EQ(v["voxel"]["later_directions"].get<int>(), 90);
  EXPECT_EQ(v["voxel"]["tail_share"].get<double>(), 0.0);
  r = run({"solve", voxel, "--later-sphere-radius", "2", "--tail-estimate", "--stats", stats,
           "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  v = readJson(stats);
  EXPECT_EQ(v["voxel"]["later_directions"].get<int>(), 26);
  EXPECT_GT(v["voxel"]["tail_share"].get<double>(), 0.0);
  r = run({"solve", scene(R"({"method": "voxel", "tail_estimate": 3})")});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("/solver/tail_estimate"), std::string::npos) << r.err;
}

// The lit mesh as a .glb that viewers open, from either method (the content is checked in
// tests/patch and tests/voxel).
TEST(Cli, SolveExportsLitMeshAsGlb) {
  const fs::path dir = freshDir("patch_glb");
  const std::string glb = (dir / "x.glb").string();
  const CliResult r = run({"solve", "cornell", "--method", "patch", "--patches", "300", "--ff-rays",
                           "16", "--export", glb, "--cache-dir", "none", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream in(glb, std::ios::binary);
  char magic[4] = {};
  in.read(magic, 4);
  EXPECT_EQ(std::string(magic, 4), "glTF");
  const CliResult voxel =
      run({"solve", "cornell", "--method", "voxel", "--voxels", "5000", "--sphere-radius", "4",
           "--export", (dir / "v.glb").string(), "--quiet"});
  ASSERT_EQ(voxel.status, 0) << voxel.err;
  std::ifstream voxelIn(dir / "v.glb", std::ios::binary);
  voxelIn.read(magic, 4);
  EXPECT_EQ(std::string(magic, 4), "glTF");
  // --exposure scales the vertex colours; the file's JSON chunk records it.
  const CliResult exposed =
      run({"solve", "cornell", "--method", "patch", "--patches", "300", "--ff-rays", "16",
           "--export", glb, "--cache-dir", "none", "--exposure", "2.5", "--quiet"});
  ASSERT_EQ(exposed.status, 0) << exposed.err;
  const std::string bytes = readBytes(glb);
  uint32_t jsonLength = 0;
  std::memcpy(&jsonLength, bytes.data() + 12, 4);
  const nlohmann::json gltf = nlohmann::json::parse(bytes.substr(20, jsonLength));
  EXPECT_EQ(gltf["asset"]["extras"]["radiosity"]["exposure_ev"], 2.5);
}

// --lightmap writes the .glb and its irradiance atlas beside it; it is refused before any work
// without a .glb export and when the scene's charts cannot fit, leaving no file.
TEST(Cli, SolveLightmapWritesTheGlbAndItsExrOrNothing) {
  const fs::path dir = freshDir("solve_lightmap");
  const std::string glb = (dir / "c.glb").string();
  const std::vector<std::string> solve{"solve",       "cornell", "--method",  "patch",
                                       "--patches",   "300",     "--ff-rays", "16",
                                       "--cache-dir", "none",    "--quiet"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = solve;
    args.insert(args.end(), extra.begin(), extra.end());
    return run(args);
  };
  const CliResult ok = with({"--export", glb, "--lightmap", "128"});
  ASSERT_EQ(ok.status, 0) << ok.err;
  EXPECT_TRUE(fs::exists(dir / "c.glb"));
  EXPECT_TRUE(fs::exists(dir / "c.lightmap.exr"));
  fs::remove_all(dir);
  fs::create_directories(dir);

  const CliResult noGlb = with({"--export", (dir / "c.csv").string(), "--lightmap", "128"});
  EXPECT_EQ(noGlb.status, 2);
  EXPECT_NE(noGlb.err.find(".glb"), std::string::npos) << noGlb.err;
  const CliResult tooSmall = with({"--export", glb, "--lightmap", "16"});
  EXPECT_EQ(tooSmall.status, 2);
  EXPECT_NE(tooSmall.err.find("--lightmap 16"), std::string::npos) << tooSmall.err;
  EXPECT_EQ(tooSmall.err.find("patches"), std::string::npos) << "refused after the solve";
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(Cli, SolveRejectsUnknownExportFormat) {
  const fs::path dir = freshDir("voxel_badexport");
  const CliResult r = run({"solve", "cornell", "--export", (dir / "v.obj").string()});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find(".csv"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(".glb"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "v.obj"));
}

}  // namespace

// Every setting is declared once (solver_settings.h): a value just outside its range gets the
// same message as a flag and as a scene key, and a value at the edge of its range is taken by
// both (before, tolerance 0 passed as a flag and failed as a key, and spp and max_depth had
// different ranges in the two).
TEST(Cli, FlagsAndSceneKeysShareEachSettingsRange) {
  const fs::path dir = freshDir("settings_once");
  writeFile(dir / "room.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  int checked = 0;
  for (const rad::SettingDeclaration& d : rad::solverSettingDeclarations()) {
    if (d.type != rad::SettingType::Integer && d.type != rad::SettingType::Number) continue;
    const double below = d.minOpen ? d.min : d.min - 1.0;
    const std::string text =
        fmt::format("{}", d.type == rad::SettingType::Integer ? int64_t(below) : below);
    const std::string why =
        d.problem(d.type == rad::SettingType::Integer ? rad::SettingValue(int64_t(below))
                                                      : rad::SettingValue(below));
    ASSERT_FALSE(why.empty()) << d.name;
    const fs::path scene = writeFile(dir / "s.json", R"({"geometry": [{"file": "room.obj"}],
      "materials": {"default": {"rho": [0.5, 0.5, 0.5], "emission": [1, 1, 1]}},
      "solver": {")" + d.name + "\": " + text + "}}");
    const CliResult key = run({"info", scene.string()});
    EXPECT_EQ(key.status, 2) << d.name;
    EXPECT_NE(key.err.find("/solver/" + d.name + ": " + why), std::string::npos) << key.err;
    const CliResult render =
        run({"render", "cornell", d.flag(), text, "-o", (dir / "x.png").string()});
    EXPECT_EQ(render.status, 2) << d.name;
    EXPECT_NE(render.err.find(d.flag() + ": " + why), std::string::npos) << render.err;
    ++checked;
  }
  EXPECT_GE(checked, 15);
  // The edge of a range is valid both ways.
  const fs::path scene = writeFile(dir / "edge.json", R"({"geometry": [{"file": "room.obj"}],
      "materials": {"default": {"rho": [0.5, 0.5, 0.5], "emission": [1, 1, 1]}},
      "solver": {"tolerance": 0, "method": "patch", "refine_levels": 0}})");
  EXPECT_EQ(run({"info", scene.string()}).status, 0);
  EXPECT_EQ(run({"solve", scene.string(), "--tolerance", "0", "--max-iterations", "3",
                 "--cache-dir", "none", "--quiet"})
                .status,
            0);
}

namespace {

// The mean irradiance (green channel) the stats file gives an object.
double meanIrradiance(const nlohmann::json& stats, const std::string& object) {
  for (const auto& o : stats["objects"])
    if (o["name"] == object) return o["mean_irradiance"][1].get<double>();
  ADD_FAILURE() << "no object " << object;
  return 0.0;
}

}  // namespace

// --time evaluates the lights' animation: a spot whose path turns it from the red wall (t = 0)
// to the green wall (t = 1) lights whichever wall its keyframe aims at.
TEST(Cli, TimeEvaluatesTheLightsPath) {
  const fs::path dir = freshDir("time");
  const std::string obj = std::string(RADIOSITY_TEST_DATA_DIR) + "/scene/cornell/cornell_box.obj";
  const fs::path scene = writeFile(dir / "spot.json", R"({"geometry": [{"file": ")" + obj + R"("}],
    "lights": [{"type": "spot", "position": [278, 400, 279.5], "direction": [1, 0, 0],
      "intensity": [2e5, 2e5, 2e5], "inner_angle_deg": 20, "outer_angle_deg": 30,
      "path": [{"t": 0, "direction": [1, 0, 0]}, {"t": 1, "direction": [-1, 0, 0]}]}]})");
  std::map<std::string, nlohmann::json> at;
  for (const std::string t : {"0", "1"}) {
    const std::string stats = (dir / ("s" + t + ".json")).string();
    const CliResult r = run({"solve", scene.string(), "--method", "patch", "--patches", "400",
                             "--cache-dir", "none", "--time", t, "--stats", stats});
    ASSERT_EQ(r.status, 0) << r.err;
    at[t] = readJson(stats);
  }
  // The Cornell data's red wall is at x = 550, the green one at x = 0; the ceiling light gives
  // both walls the same at either time, the spot a wall at one time only.
  EXPECT_GT(meanIrradiance(at["0"], "left_wall_red"),
            1.3 * meanIrradiance(at["1"], "left_wall_red"));
  EXPECT_GT(meanIrradiance(at["1"], "right_wall_green"),
            1.3 * meanIrradiance(at["0"], "right_wall_green"));
  EXPECT_EQ(run({"solve", scene.string(), "--time", "soon"}).status, 2);
}

// --group: the groups solved apart and combined at the scales asked; the stats give each group's
// scale and power (the emitted energy is theirs) and its share of every object's light.
TEST(Cli, GroupFlagsScaleLightGroupsAndTheStatsShareTheLight) {
  const fs::path dir = freshDir("groups");
  const std::string obj = std::string(RADIOSITY_TEST_DATA_DIR) + "/scene/cornell/cornell_box.obj";
  const fs::path scene = writeFile(dir / "lamps.json", R"({"geometry": [{"file": ")" + obj + R"("}],
    "lights": [{"type": "spot", "group": "spot", "position": [278, 400, 279.5],
                "direction": [1, -0.3, 0], "intensity": [2e5, 1e5, 5e4],
                "inner_angle_deg": 20, "outer_angle_deg": 30},
               {"type": "point", "position": [420, 300, 150], "intensity": [1e4, 1e4, 2e4]}]})");
  const std::string stats = (dir / "stats.json").string();
  const CliResult r =
      run({"solve", scene.string(), "--method", "patch", "--patches", "400", "--cache-dir", "none",
           "--group", "spot=0", "--group", "light=0.5,1,1", "--stats", stats});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = readJson(stats);
  ASSERT_EQ(j["light_groups"].size(), 3u);
  EXPECT_EQ(j["light_groups"][0]["name"], "spot");
  EXPECT_EQ(j["light_groups"][0]["power"][0].get<double>(), 0.0);
  EXPECT_EQ(j["light_groups"][1]["name"], "light1");  // the point light: a group of its own
  EXPECT_EQ(j["light_groups"][2]["name"], "light");   // the OBJ's emitting material
  EXPECT_EQ(j["light_groups"][2]["scale"][0].get<double>(), 0.5);
  // The point light's power, 4 pi I, and the lamp's at its scale make the emitted energy.
  const double point = 4.0 * 3.14159265358979 * 1e4;
  EXPECT_NEAR(j["light_groups"][1]["power"][0].get<double>(), point, 1e-6 * point);
  const double emitted = j["energy"]["emitted"][0].get<double>();
  EXPECT_NEAR(emitted, point + j["light_groups"][2]["power"][0].get<double>(), 1e-5 * emitted);
  for (const auto& o : j["objects"]) {
    const nlohmann::json& shares = o["group_shares"];
    EXPECT_EQ(shares["spot"].get<double>(), 0.0) << o["name"];
    EXPECT_NEAR(shares["light1"].get<double>() + shares["light"].get<double>(), 1.0, 1e-6);
  }

  const CliResult unknown = run({"solve", scene.string(), "--group", "lamp=0"});
  EXPECT_EQ(unknown.status, 2);
  EXPECT_NE(unknown.err.find("spot, light1, light"), std::string::npos) << unknown.err;
  EXPECT_EQ(run({"solve", scene.string(), "--group", "spot=dim"}).status, 2);
}

// solve --save writes a solution that render --solution draws without solving: the same picture
// bit for bit as a render that solves, with its light groups rescaled on the way; bad names and
// files are refused.
TEST(Cli, RenderFromASavedSolutionWithoutSolving) {
  const fs::path dir = freshDir("solution");
  const std::string rad = (dir / "box.rad").string();
  const std::vector<std::string> method = {"--method",    "patch", "--patches",     "300",
                                           "--cache-dir", "none",  "--light-groups"};
  std::vector<std::string> solve = {"solve", "cornell-spot", "--save", rad};
  solve.insert(solve.end(), method.begin(), method.end());
  const CliResult saved = run(solve);
  ASSERT_EQ(saved.status, 0) << saved.err;
  std::vector<std::string> render = {"render",  "cornell-spot", "-o",    (dir / "a.pfm").string(),
                                     "--width", "40",           "--spp", "1"};
  render.insert(render.end(), method.begin(), method.end());
  ASSERT_EQ(run(render).status, 0);
  const CliResult loaded = run({"render", "cornell-spot", "--solution", rad, "-o",
                                (dir / "b.pfm").string(), "--width", "40", "--spp", "1"});
  ASSERT_EQ(loaded.status, 0) << loaded.err;
  EXPECT_EQ(readBytes((dir / "a.pfm").string()), readBytes((dir / "b.pfm").string()));
  const CliResult dimmed =
      run({"render", "cornell-spot", "--solution", rad, "-o", (dir / "c.pfm").string(), "--width",
           "40", "--group", "light0=0.5"});
  ASSERT_EQ(dimmed.status, 0) << dimmed.err;
  EXPECT_LT(meanRadiance(rad::readImage((dir / "c.pfm").string())),
            0.6 * meanRadiance(rad::readImage((dir / "b.pfm").string())));

  EXPECT_EQ(run({"solve", "cornell-spot", "--save", (dir / "box.bin").string()}).status, 2);
  EXPECT_EQ(run({"solve", "cornell-spot", "--save", (dir / "no/box.rad").string()}).status, 2);
  const CliResult missing = run({"render", "cornell-spot", "--solution", (dir / "x.rad").string()});
  EXPECT_EQ(missing.status, 2);
  EXPECT_NE(missing.err.find("no such solution file"), std::string::npos) << missing.err;
  const CliResult foreign = run({"render", "cornell", "--solution", rad});
  EXPECT_EQ(foreign.status, 2);
  EXPECT_NE(foreign.err.find("another scene"), std::string::npos) << foreign.err;
  // An empty path is a mistake (before: render path-traced without a word), for every command
  // that takes a solution; and solve takes none (its --save help says which do).
  for (const std::string command : {"render", "animate", "serve"}) {
    const CliResult empty = run({command, "cornell-spot", "--solution", ""});
    EXPECT_EQ(empty.status, 2) << command;
    EXPECT_NE(empty.err.find("--solution"), std::string::npos) << command << ": " << empty.err;
  }
  EXPECT_EQ(run({"solve", "cornell-spot", "--solution", rad}).status, 2);
  const CliResult help = run({"solve", "--help"});
  EXPECT_NE(help.out.find("render, animate and serve --solution"), std::string::npos) << help.out;
}

// A dynamic object moves along its path between --time values, lit by a probe in patch pictures
// (with a warning of what is not computed yet) and taken as it is by the path tracer.
TEST(Cli, RendersDynamicObjectsWhereTheirPathPutsThem) {
  const fs::path dir = freshDir("dynamic");
  writeFile(dir / "cube.obj",
            "o cube\nv -40 -40 -40\nv 40 -40 -40\nv 40 40 -40\nv -40 40 -40\n"
            "v -40 -40 40\nv 40 -40 40\nv 40 40 40\nv -40 40 40\n"
            "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n");
  const std::string obj = std::string(RADIOSITY_TEST_DATA_DIR) + "/scene/cornell/cornell_box.obj";
  const fs::path scene =
      writeFile(dir / "moving.json", R"({"geometry": [{"file": ")" + obj + R"("}],
    "dynamic_objects": [{"name": "box", "file": "cube.obj", "rho": [0.8, 0.8, 0.8],
      "path": [{"t": 0, "position": [150, 250, 250]}, {"t": 1, "position": [400, 250, 250]}]}],
    "camera": {"eye": [278, 273, -800], "target": [278, 273, 0], "fov_deg": 39}})");
  std::map<std::string, rad::Image> at;
  for (const std::string t : {"0", "1"}) {
    const std::string png = (dir / ("p" + t + ".pfm")).string();
    const std::string stats = (dir / ("s" + t + ".json")).string();
    const CliResult r =
        run({"render", scene.string(), "--method", "patch", "--patches", "400", "--cache-dir",
             "none", "--width", "64", "--spp", "1", "--time", t, "-o", png, "--stats", stats});
    ASSERT_EQ(r.status, 0) << r.err;
    // The stats hold the object's light: its mean irradiance and what it sends along each axis
    // (its top, lit by the lamp above, sends more up than its bottom sends down).
    const nlohmann::json j = readJson(stats);
    ASSERT_EQ(j["dynamic_objects"].size(), 1u);
    EXPECT_EQ(j["dynamic_objects"][0]["name"], "box");
    EXPECT_GT(j["dynamic_objects"][0]["mean_irradiance"][1].get<double>(), 0.0);
    const nlohmann::json& lobes = j["dynamic_objects"][0]["lobes"];
    EXPECT_GT(lobes["+y"][1].get<double>(), lobes["-y"][1].get<double>());
    EXPECT_NE(r.err.find("dynamic object(s) lit by probes"), std::string::npos) << r.err;
    at[t] = rad::readImage(png);
  }
  size_t differing = 0;
  for (size_t k = 0; k < at["0"].pixels.size(); ++k)
    differing += rad::maxComponent(glm::abs(at["0"].pixels[k] - at["1"].pixels[k])) > 0.05f;
  EXPECT_GT(differing, 40u);  // the cube left one place for another
  // The lit mesh exported with the object as a node of its own.
  const std::string glb = (dir / "moving.glb").string();
  ASSERT_EQ(run({"solve", scene.string(), "--method", "patch", "--patches", "300", "--cache-dir",
                 "none", "--export", glb})
                .status,
            0);
  EXPECT_NE(readBytes(glb).find("\"name\":\"box\""), std::string::npos);
  const CliResult traced = run({"render", scene.string(), "--method", "pathtrace", "--width", "32",
                                "--spp", "4", "-o", (dir / "t.pfm").string()});
  EXPECT_EQ(traced.status, 0) << traced.err;
}
