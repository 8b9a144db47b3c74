// `radiosity bench distributed`: one voxel solve on one process with one thread against the same
// solve under `mpirun -np N` with one thread a rank, side by side in one run (alternating, the
// fastest of each): the parallel efficiency T1 / (N TN) of the split (mpi_processes.h), the
// bytes rank 0 moved and the ranks' load balance, from the runs' stats files.
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>

#include "bench_workloads.h"
#include "child_process.h"

namespace rad::cli {

nlohmann::json benchDistributed(Console& console, int ranks, size_t voxels) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / fmt::format("radiosity-bench-{}", getpid());
  std::filesystem::create_directories(dir);
  const std::string self = selfExecutable();
  auto solve = [&](const std::string& stats) {
    return std::vector<std::string>{self,
                                    "--threads",
                                    "1",
                                    "-q",
                                    "solve",
                                    "room:16",
                                    "--method",
                                    "voxel",
                                    "--voxels",
                                    std::to_string(voxels),
                                    "--sphere-radius",
                                    "12",
                                    "--cache-dir",
                                    "none",
                                    "--stats",
                                    stats};
  };
  std::vector<std::string> mpirun{"mpirun", "--oversubscribe", "-np", std::to_string(ranks)};
  if (geteuid() == 0) mpirun.insert(mpirun.begin() + 1, "--allow-run-as-root");
  double alone = std::numeric_limits<double>::max(), split = alone;
  nlohmann::json distributed;
  constexpr int kRounds = 2;
  for (int round = 0; round < kRounds; ++round) {
    console.info(fmt::format("bench distributed: round {} of {}", round + 1, kRounds));
    const std::string one = (dir / "one.json").string(), many = (dir / "split.json").string();
    runToCompletion(solve(one));
    std::vector<std::string> args = mpirun;
    const std::vector<std::string> rest = solve(many);
    args.insert(args.end(), rest.begin(), rest.end());
    runToCompletion(args);
    const nlohmann::json a = nlohmann::json::parse(std::ifstream(one));
    const nlohmann::json b = nlohmann::json::parse(std::ifstream(many));
    alone = std::min(alone, a["timings_s"]["solve"].get<double>());
    const double s = b["timings_s"]["solve"].get<double>();
    if (s < split) split = s, distributed = b["distributed"];
  }
  std::filesystem::remove_all(dir);
  const double efficiency = alone / (double(ranks) * split);
  return {{"scene", "room:16"},
          {"voxels", voxels},
          {"sphere_radius", 12},
          {"ranks", ranks},
          {"solve_seconds_one_process", alone},
          {"solve_seconds_split", split},
          {"parallel_efficiency", efficiency},
          {"distributed", distributed},
          {"summary",
           fmt::format("{} ranks x 1 thread: solve {:.2f} s against {:.2f} s on one process x 1 "
                       "thread, parallel efficiency {:.2f} (room:16, {} voxels, R = 12)",
                       ranks, split, alone, efficiency, voxels)}};
}

}  // namespace rad::cli
