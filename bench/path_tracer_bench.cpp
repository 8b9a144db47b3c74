// Throughput of the reference path tracer and of the ray caster under it, in rays per second,
// on a hand-built Cornell-like box (five walls, a ceiling light, two blocks; 1 unit wide).
#include <benchmark/benchmark.h>
#include <radiosity/path_tracer.h>
#include <radiosity/ray_caster.h>
#include <radiosity/scene_builder.h>

#include <array>
#include <vector>

#include "core/rng.h"

namespace rad {
namespace {

// An axis-aligned box [lo, hi] as six quads whose front faces point outward (or inward).
void addBox(SceneBuilder& b, const Vec3& lo, const Vec3& hi, bool inward,
            const std::array<uint32_t, 6>& materials, bool skipFront, const char* name) {
  const uint32_t object = b.addObject(name);
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      if (skipFront && axis == 2 && side == 1) continue;  // the open side faces +z
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const float c = side ? hi[axis] : lo[axis];
      std::array<Vec3, 4> q;
      const float us[4] = {lo[u], hi[u], hi[u], lo[u]}, vs[4] = {lo[v], lo[v], hi[v], hi[v]};
      for (int k = 0; k < 4; ++k) {
        q[k][axis] = c;
        q[k][u] = us[k];
        q[k][v] = vs[k];
      }
      // (u, v) winding is counter-clockwise about +axis; flip it where the front must face -axis.
      const bool facesPlus = (side == 1) != inward;
      if (!facesPlus) std::swap(q[1], q[3]);
      std::array<uint32_t, 4> ids;
      for (int k = 0; k < 4; ++k) ids[k] = b.addVertex(q[k], "bench");
      b.addPolygon(ids, materials[size_t(axis * 2 + side)], object, "bench");
    }
}

Scene cornellLikeBox() {
  SceneBuilder b("cornell-like");
  Material white, red, green, lamp;
  white.rho = Color(0.73f);
  red.rho = Color(0.63f, 0.06f, 0.05f);
  green.rho = Color(0.14f, 0.45f, 0.09f);
  lamp.rho = Color(0.78f);
  lamp.emission = Color(17.0f, 12.0f, 4.0f);
  const uint32_t w = b.addMaterial(white), r = b.addMaterial(red), g = b.addMaterial(green),
                 l = b.addMaterial(lamp);
  addBox(b, Vec3(0.0f), Vec3(1.0f), true, {r, g, w, w, w, w}, true, "room");
  addBox(b, Vec3(0.35f, 0.999f, 0.4f), Vec3(0.65f, 1.0f, 0.6f), false, {w, w, l, w, w, w}, false,
         "light");
  addBox(b, Vec3(0.15f, 0.0f, 0.45f), Vec3(0.45f, 0.6f, 0.75f), false, {w, w, w, w, w, w}, false,
         "tall block");
  addBox(b, Vec3(0.55f, 0.0f, 0.15f), Vec3(0.85f, 0.3f, 0.45f), false, {w, w, w, w, w, w}, false,
         "short block");
  return b.build();
}

Camera frontView(int size) {
  Camera c;
  c.eye = Vec3(0.5f, 0.5f, 1.95f);
  c.target = Vec3(0.5f, 0.5f, 0.0f);
  c.fovDeg = 39.0f;
  c.width = c.height = size;
  return c;
}

void BM_PathTracerCornell(benchmark::State& state) {
  const Scene scene = cornellLikeBox();
  PathTracerSettings settings;
  settings.samplesPerPixel = int(state.range(0));
  uint64_t rays = 0, paths = 0;
  for (auto _ : state) {
    const PathTracedImage result = renderPathTraced(scene, frontView(128), settings);
    rays += result.stats.rays;
    paths += result.stats.paths;
    benchmark::DoNotOptimize(result.image.pixels.data());
  }
  state.counters["rays"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
  state.counters["paths"] = benchmark::Counter(double(paths), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PathTracerCornell)->Arg(16)->Unit(benchmark::kMillisecond)->UseRealTime();

// Incoherent rays from random points inside the room to random directions (single thread).
std::vector<Ray> randomRays(size_t n) {
  Rng rng(11, 0);
  std::vector<Ray> rays(n);
  for (Ray& r : rays) {
    r.origin = Vec3(0.05f + 0.9f * rng.uniform(), 0.65f + 0.3f * rng.uniform(),
                    0.05f + 0.9f * rng.uniform());
    const Vec3 d(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f);
    r.direction = glm::normalize(d + Vec3(0.0f, 0.0f, 1e-3f));
  }
  return rays;
}

void BM_RayCasterClosestHit(benchmark::State& state) {
  const RayCaster caster(cornellLikeBox());
  const std::vector<Ray> rays = randomRays(1 << 16);
  std::vector<Hit> hits(rays.size());
  const bool batch = state.range(0) != 0;
  for (auto _ : state) {
    if (batch) {
      caster.intersect(rays, hits);
    } else {
      for (size_t i = 0; i < rays.size(); ++i) hits[i] = caster.intersect(rays[i]);
    }
    benchmark::DoNotOptimize(hits.data());
  }
  state.counters["rays"] =
      benchmark::Counter(double(state.iterations() * rays.size()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RayCasterClosestHit)->ArgName("batch")->Arg(0)->Arg(1);

void BM_RayCasterOccluded(benchmark::State& state) {
  const RayCaster caster(cornellLikeBox());
  const std::vector<Ray> rays = randomRays(1 << 16);
  std::vector<uint8_t> blocked(rays.size());
  for (auto _ : state) {
    caster.occluded(rays, blocked);
    benchmark::DoNotOptimize(blocked.data());
  }
  state.counters["rays"] =
      benchmark::Counter(double(state.iterations() * rays.size()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RayCasterOccluded);

}  // namespace
}  // namespace rad
