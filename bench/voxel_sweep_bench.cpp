// Throughput of the voxel method's kernels on the furnished room the CLI benchmarks use
// (`room:16`): the sweep of one direction pair in voxel-direction visits per second (one thread),
// and the voxelization in voxels per second.
#include <benchmark/benchmark.h>
#include <radiosity/scene_loader.h>
#include <tbb/global_control.h>

#include <map>
#include <vector>

#include "voxel/direction_set.h"
#include "voxel/discrete_line_sweep.h"
#include "voxel/voxelizer.h"

namespace rad {
namespace {

// One grid per voxel count, built once: voxelizing the larger rooms takes longer than a sweep.
const VoxelGrid& roomGrid(size_t voxels) {
  static std::map<size_t, VoxelGrid> grids;
  auto it = grids.find(voxels);
  if (it == grids.end()) {
    VoxelizerSettings settings;
    settings.targetVoxels = voxels;
    it = grids.emplace(voxels, voxelizeScene(loadScene("room:16"), settings)).first;
  }
  return it->second;
}

// Sweeps of direction pairs spread over the R = 38 sphere (every 97th pair: all octants and
// dominant axes), each sending a uniform radiosity, so that every side's look is exercised.
void BM_DiscreteLineSweepPair(benchmark::State& state) {
  const VoxelGrid& grid = roomGrid(size_t(state.range(0)));
  const DirectionSet directions(38);
  std::vector<DiscreteLineSweep::SentLight> slots(grid.entryCount());
  const DiscreteLineSweep::Source source = DiscreteLineSweep::packSides(
      grid, [](size_t) { return Color(1.0f); }, slots);
  std::vector<Color> gathered(grid.entryCount());
  // One thread: the kernel's own rate (a sweep shares each direction among all threads).
  const tbb::global_control oneThread(tbb::global_control::max_allowed_parallelism, 1);
  DiscreteLineSweep sweep(grid, {});
  size_t k = 0, pairs = 0;
  for (auto _ : state) {
    sweep.sweepPair(directions.pairFirst(k), source, gathered);
    k = (k + 97) % directions.pairCount();
    ++pairs;
  }
  benchmark::DoNotOptimize(gathered.data());
  // A pair visits every cell once for each of its two directions.
  state.counters["visits"] = benchmark::Counter(double(pairs) * 2.0 * double(grid.cellCount()),
                                                benchmark::Counter::kIsRate);
  state.counters["cells"] = double(grid.cellCount());
}
BENCHMARK(BM_DiscreteLineSweepPair)
    ->ArgName("voxels")
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond);

void BM_Voxelize(benchmark::State& state) {
  const Scene scene = loadScene("room:16");
  VoxelizerSettings settings;
  settings.targetVoxels = size_t(state.range(0));
  size_t cells = 0;
  for (auto _ : state) {
    const VoxelGrid grid = voxelizeScene(scene, settings);
    cells += grid.cellCount();
    benchmark::DoNotOptimize(grid.orientation.data());
  }
  state.counters["voxels"] = benchmark::Counter(double(cells), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Voxelize)->ArgName("voxels")->Arg(200000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace rad
