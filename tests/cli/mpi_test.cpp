// `mpirun -np N radiosity solve ... --method voxel`: one solve split among processes gives the
// single process's answer bit for bit, written once by rank 0; a rank
// killed takes the job down with no output. Skipped where the tool was built without MPI or
// mpirun is missing.
#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "cli_run.h"

namespace rad {
namespace {

namespace fs = std::filesystem;
using test::freshDir;
using test::readBytes;
using test::readJson;

const std::string kBinary = std::string(RADIOSITY_BINARY_DIR) + "/radiosity";
// mpirun refuses root unless told; the test machines run as root.
const std::string kMpirun =
    "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun --oversubscribe ";

bool mpiAvailable() {
#ifdef RADIOSITY_HAS_MPI
  return std::system("command -v mpirun > /dev/null 2>&1") == 0;
#else
  return false;
#endif
}

// The voxel solve of the Cornell box the tests split: small, one thread a process.
std::string voxelSolve(const fs::path& dir, const std::string& name) {
  return kBinary + " --threads 1 -q solve cornell --method voxel --voxels 20000 " +
         "--sphere-radius 8 --cache-dir none --export " + (dir / (name + ".csv")).string() +
         " --stats " + (dir / (name + ".json")).string();
}

TEST(Mpi, SplitVoxelSolveMatchesOneProcess) {
  if (!mpiAvailable()) GTEST_SKIP() << "built without MPI or no mpirun";
  const fs::path dir = freshDir("mpi_split");
  ASSERT_EQ(std::system(voxelSolve(dir, "one").c_str()), 0);
  for (const int ranks : {2, 3}) {
    const std::string name = "np" + std::to_string(ranks);
    ASSERT_EQ(std::system(
                  (kMpirun + "-np " + std::to_string(ranks) + " " + voxelSolve(dir, name)).c_str()),
              0);
    // The same bounce, bit for bit: the direction pairs go in fixed blocks whatever the rank
    // count, and the blocks' light is added exactly (integers), so every side's irradiance and
    // every object's are one process's.
    const nlohmann::json one = readJson((dir / "one.json").string());
    const nlohmann::json split = readJson((dir / (name + ".json")).string());
    EXPECT_EQ(one["objects"], split["objects"]) << ranks << " ranks";
    EXPECT_EQ(readBytes((dir / "one.csv").string()), readBytes((dir / (name + ".csv")).string()))
        << ranks << " ranks";
    EXPECT_EQ(split["distributed"]["ranks"].get<int>(), ranks);
    EXPECT_GT(split["distributed"]["bytes_communicated_rank0"].get<double>(), 0.0);
  }
  // The same rank count again: the same bytes.
  ASSERT_EQ(std::system((kMpirun + "-np 2 " + voxelSolve(dir, "np2_again")).c_str()), 0);
  EXPECT_EQ(readBytes((dir / "np2.csv").string()), readBytes((dir / "np2_again.csv").string()));
  // Only rank 0 wrote: no other file, no temporary.
  size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 8u);
}

TEST(Mpi, SplitPatchSolveIsTheOneProcessSolve) {
  // The hemisphere rows cast in blocks and exchanged: every rank holds the rows one process
  // casts (each row's rays are its own stream's), so the export is the same, byte for byte;
  // Jacobi's sweeps computed in blocks and gathered likewise, and the other estimators' rows.
  if (!mpiAvailable()) GTEST_SKIP() << "built without MPI or no mpirun";
  const fs::path dir = freshDir("mpi_patch");
  auto solve = [&](const std::string& name) {
    return kBinary + " --threads 1 -q solve cornell-spot --method patch --cache-dir none " +
           "--export " + (dir / (name + ".csv")).string();
  };
  ASSERT_EQ(std::system(solve("one").c_str()), 0);
  for (const std::string ranks : {"2", "3"}) {
    ASSERT_EQ(std::system((kMpirun + "-np " + ranks + " " + solve("np" + ranks)).c_str()), 0);
    EXPECT_EQ(readBytes((dir / "one.csv").string()),
              readBytes((dir / ("np" + ranks + ".csv")).string()))
        << ranks << " ranks";
  }
  // Jacobi sweeps split too: each rank its block of the patches, the sweep's H and B gathered.
  const std::string jacobi = " --solver jacobi --tolerance 1e-5";
  ASSERT_EQ(std::system((solve("jacobi_one") + jacobi).c_str()), 0);
  for (const std::string ranks : {"2", "3"}) {
    ASSERT_EQ(
        std::system((kMpirun + "-np " + ranks + " " + solve("jacobi_np" + ranks) + jacobi).c_str()),
        0);
    EXPECT_EQ(readBytes((dir / "jacobi_one.csv").string()),
              readBytes((dir / ("jacobi_np" + ranks + ".csv")).string()))
        << ranks << " ranks, Jacobi";
  }
  // The exact and pairwise estimators' rows, every count-th a rank, exchanged likewise.
  for (const std::string estimator : {"exact", "pairwise"}) {
    const std::string flags = " --ff-estimator " + estimator + " --patches 300 --ff-rays 16";
    ASSERT_EQ(std::system((solve(estimator + "_one") + flags).c_str()), 0);
    ASSERT_EQ(std::system((kMpirun + "-np 3 " + solve(estimator + "_np3") + flags).c_str()), 0);
    EXPECT_EQ(readBytes((dir / (estimator + "_one.csv")).string()),
              readBytes((dir / (estimator + "_np3.csv")).string()))
        << estimator;
  }
}

TEST(Mpi, KilledRankEndsTheJobWithoutOutput) {
  if (!mpiAvailable()) GTEST_SKIP() << "built without MPI or no mpirun";
  const fs::path dir = freshDir("mpi_kill");
  // A solve long enough to be killed in (200k voxels, R = 16), rank 1 killed after a second.
  const std::string solve = kBinary + " --threads 1 -q solve cornell --method voxel --voxels " +
                            "200000 --sphere-radius 16 --cache-dir none --export " +
                            (dir / "killed.csv").string();
  const std::string killer =
      "(sleep 2; for p in $(pgrep -f 'voxels 200000 --sphere-radius 16'); do "
      "grep -qz OMPI_COMM_WORLD_RANK=1 /proc/$p/environ 2>/dev/null && kill -9 $p; done) & ";
  const int status = std::system(
      (killer + kMpirun + "-np 2 " + solve + " 2> " + (dir / "err.txt").string()).c_str());
  EXPECT_NE(status, 0);
  EXPECT_FALSE(fs::exists(dir / "killed.csv"));
  size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1u);  // err.txt alone
}

TEST(Mpi, BenchComparesTheSplitWithOneProcess) {
  if (!mpiAvailable()) GTEST_SKIP() << "built without MPI or no mpirun";
  const fs::path dir = freshDir("mpi_bench");
  const std::string json = (dir / "bench.json").string();
  ASSERT_EQ(
      std::system(
          (kBinary + " bench distributed --distributed-voxels 5000 --json > " + json).c_str()),
      0);
  const nlohmann::json b = readJson(json)["distributed"];
  EXPECT_EQ(b["ranks"].get<int>(), 2);
  EXPECT_EQ(b["distributed"]["ranks"].get<int>(), 2);
  EXPECT_GT(b["parallel_efficiency"].get<double>(), 0.0);
  EXPECT_GT(b["solve_seconds_one_process"].get<double>(), 0.0);
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

// The path tracer split among 2 and 3 processes (every count-th tile each, and every count-th of
// the per-object estimate's points, added up): the same picture as one process, bit for bit, the
// same per-object numbers and the same rays counted.
TEST(Mpi, SplitPathTracedRenderIsTheSamePicture) {
  if (!mpiAvailable()) GTEST_SKIP() << "built without MPI or no mpirun";
  const fs::path dir = freshDir("mpi_pathtrace");
  auto render = [&](const std::string& name) {
    return kBinary + " --threads 1 -q render cornell --method pathtrace --spp 4 --width 80 " +
           "--height 60 --cache-dir none --object-points 16 -o " +
           (dir / (name + ".pfm")).string() + " --stats " + (dir / (name + ".json")).string();
  };
  ASSERT_EQ(std::system(render("one").c_str()), 0);
  const std::string picture = readBytes((dir / "one.pfm").string());
  const nlohmann::json one = readJson((dir / "one.json").string());
  for (const int ranks : {2, 3}) {
    const std::string name = "np" + std::to_string(ranks);
    ASSERT_EQ(std::system((kMpirun + "-np " + std::to_string(ranks) + " " + render(name)).c_str()),
              0);
    EXPECT_TRUE(readBytes((dir / (name + ".pfm")).string()) == picture) << ranks;
    const nlohmann::json stats = readJson((dir / (name + ".json")).string());
    EXPECT_EQ(stats["counts"]["rays"], one["counts"]["rays"]) << ranks;
    EXPECT_EQ(stats["objects"], one["objects"]) << ranks;
    EXPECT_EQ(stats["distributed"]["ranks"].get<int>(), ranks);
  }
}

}  // namespace
}  // namespace rad
