#include <fmt/format.h>
#include <radiosity/path_tracer.h>
#include <radiosity/scene_loader.h>

#include "bench_workloads.h"

namespace rad::cli {

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
  const double raysPerSecond = double(s.rays) / s.seconds;
  return {{"scene", "cornell"},
          {"width", camera.width},
          {"height", camera.height},
          {"spp", settings.samplesPerPixel},
          {"seconds", s.seconds},
          {"rays", s.rays},
          {"rays_per_s", raysPerSecond},
          {"paths_per_s", double(s.paths) / s.seconds},
          {"summary",
           fmt::format("{:.2f} Mrays/s, {:.2f} Mpaths/s (cornell 128x128 at 32 spp, {:.2f} s)",
                       raysPerSecond * 1e-6, double(s.paths) / s.seconds * 1e-6, s.seconds)}};
}

}  // namespace rad::cli
