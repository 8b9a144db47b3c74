// `radiosity bench [pathtrace|patch|relight|probe|voxel|all|voxel-scaling|interior|distributed]
// [--json]`: throughput
// numbers that notes and reports quote. Fixed workloads on built-in scenes, so numbers from
// different machines compare.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <ostream>

#include "bench_workloads.h"
#include "commands.h"

namespace rad::cli {

namespace {

struct BenchOptions {
  std::string which = "all";
  bool json = false;
  size_t voxels = 2000000;
  int sphereRadius = 38;
  size_t pairStride = 24;
  int scalingRadius = 8;
  size_t scalingMaxVoxels = 4000000;
  std::string output = "bench_out";
  size_t relightPatches = 10000;
  int relightFrames = 0;
  int probeResolution = 16;  ///< 0: the default period
  int interiorDetail = 180;
  int ranks = 2;
  size_t distributedVoxels = 300000;
};

int runBench(const BenchOptions& o, Console& console) {
  nlohmann::json results;
  const bool all = o.which == "all";
  if (all || o.which == "pathtrace") results["pathtrace"] = benchPathTracer(console);
  if (all || o.which == "patch") results["patch"] = benchPatch(console);
  if (all || o.which == "relight")
    results["relight"] = benchRelight(console, o.relightPatches, o.relightFrames);
  if (all || o.which == "probe") results["probe"] = benchProbe(console, o.probeResolution);
  if (all || o.which == "voxel")
    results["voxel"] = benchVoxel(console, o.voxels, o.sphereRadius, o.pairStride);
  if (o.which == "interior") results["interior"] = benchInterior(console, o.interiorDetail);
  if (o.which == "distributed")
    results["distributed"] = benchDistributed(console, o.ranks, o.distributedVoxels);
  if (o.which == "voxel-scaling")
    results["voxel-scaling"] =
        benchVoxelScaling(console, o.scalingRadius, o.scalingMaxVoxels, o.output);
  if (o.json) {
    console.out() << results.dump(2) << "\n";
    return 0;
  }
  for (const auto& [name, r] : results.items())
    console.out() << fmt::format("{:<14} {}\n", name, r["summary"].get<std::string>());
  return 0;
}

}  // namespace

void addBenchCommand(CLI::App& app, Console& console, CommandAction& action) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* sub = app.add_subcommand("bench", "Measure throughput on fixed workloads");
  sub->add_option("which", o->which,
                  "What to measure: pathtrace, patch, relight, probe, voxel, all (those five), "
                  "voxel-scaling, interior, distributed (minutes each)")
      ->check(CLI::IsMember({"pathtrace", "patch", "relight", "probe", "voxel", "voxel-scaling",
                             "interior", "distributed", "all"}));
  sub->add_option("--voxels", o->voxels,
                  "voxel: surface voxels of the room (default 2000000, the paper's)")
      ->check(CLI::Range(size_t(1000), size_t(1) << 30));
  sub->add_option("--sphere-radius", o->sphereRadius, "voxel: sphere radius R (default 38)")
      ->check(CLI::Range(1, 200));
  sub->add_option("--pair-stride", o->pairStride,
                  "voxel: sweep every Nth direction pair of the sphere (default 24; 1: all)")
      ->check(CLI::Range(size_t(1), size_t(1) << 20));
  sub->add_option("--relight-patches", o->relightPatches,
                  "relight: patches of the room (default 10000)")
      ->check(CLI::Range(size_t(100), size_t(1) << 24));
  sub->add_option("--relight-frames", o->relightFrames,
                  "relight: frames of warm-up and then measured (default: a swing's period of 240, "
                  "then half of one); fewer for large meshes")
      ->check(CLI::Range(1, 100000));
  sub->add_option("--probe-res", o->probeResolution, "probe: texels a cube face (default 16)")
      ->check(CLI::Range(1, 1024));
  sub->add_option("--scaling-radius", o->scalingRadius, "voxel-scaling: sphere radius (default 8)")
      ->check(CLI::Range(1, 200));
  sub->add_option("--scaling-max-voxels", o->scalingMaxVoxels,
                  "voxel-scaling: largest voxel count (default 4000000)");
  sub->add_option("--output-dir", o->output, "voxel-scaling: where the table and plot go");
  sub->add_option("--ranks", o->ranks,
                  "distributed: MPI ranks of the split run, one thread each (default 2)")
      ->check(CLI::Range(2, 1024));
  sub->add_option("--distributed-voxels", o->distributedVoxels,
                  "distributed: surface voxels of the room (default 300000)")
      ->check(CLI::Range(size_t(1000), size_t(1) << 30));
  sub->add_option("--interior-detail", o->interiorDetail,
                  "interior: N of atrium-textured:N (default 180: 252k triangles)")
      ->check(CLI::Range(1, 2000));
  sub->add_flag("--json", o->json, "Print the results as JSON");
  sub->callback(
      [o, &console, &action] { action = [o, &console] { return runBench(*o, console); }; });
}

}  // namespace rad::cli
