// `radiosity bench [pathtrace|all] [--json]`: throughput numbers that notes and reports quote.
// Fixed workloads on built-in scenes, so numbers from different machines compare.
#include "commands.h"

#include <radiosity/path_tracer.h>
#include <radiosity/scene_loader.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <memory>
#include <ostream>

namespace rad::cli {

namespace {

struct BenchOptions {
  std::string which = "all";
  bool json = false;
};

// The reference path tracer on the Cornell box: 128x128 pixels, 32 samples per pixel.
nlohmann::json benchPathTracer(Console& console) {
  const Scene scene = loadScene("cornell");
  Camera camera = scene.cameraOrDefault();
  camera.width = camera.height = 128;
  PathTracerSettings settings;
  settings.samplesPerPixel = 32;
  const PathTracedImage result =
      renderPathTraced(scene, camera, settings, console.progress("bench pathtrace"));
  console.finishProgress();
  const PathTracerStats& s = result.stats;
  return {{"scene", "cornell"},
          {"width", camera.width},
          {"height", camera.height},
          {"spp", settings.samplesPerPixel},
          {"seconds", s.seconds},
          {"rays", s.rays},
          {"rays_per_s", double(s.rays) / s.seconds},
          {"paths_per_s", double(s.paths) / s.seconds}};
}

int runBench(const BenchOptions& o, Console& console) {
  nlohmann::json results;
  if (o.which == "pathtrace" || o.which == "all") results["pathtrace"] = benchPathTracer(console);
  if (o.json) {
    console.out() << results.dump(2) << "\n";
    return 0;
  }
  for (const auto& [name, r] : results.items())
    console.out() << fmt::format("{:<10} {:>8.2f} Mrays/s  {:>8.2f} Mpaths/s  ({} {}x{} at {} spp, "
                                 "{:.2f} s)\n",
                                 name, r["rays_per_s"].get<double>() * 1e-6,
                                 r["paths_per_s"].get<double>() * 1e-6, r["scene"].get<std::string>(),
                                 r["width"].get<int>(), r["height"].get<int>(), r["spp"].get<int>(),
                                 r["seconds"].get<double>());
  return 0;
}

}  // namespace

void addBenchCommand(CLI::App& app, Console& console, CommandAction& action) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* sub = app.add_subcommand("bench", "Measure throughput on fixed workloads");
  sub->add_option("which", o->which, "What to measure")->check(CLI::IsMember({"pathtrace", "all"}));
  sub->add_flag("--json", o->json, "Print the results as JSON");
  sub->callback([o, &console, &action] { action = [o, &console] { return runBench(*o, console); }; });
}

}  // namespace rad::cli
