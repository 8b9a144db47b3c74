#include "patch/light_refinement.h"

#include <tbb/parallel_for.h>

#include <algorithm>

#include "core/progress_ticker.h"

namespace rad {

namespace {

// Calls f(a, b) for the patches that share a corner (a pair that shares an edge comes twice).
template <class F>
void forEachNeighbourPair(const PatchMesh& mesh, F&& f) {
  // The patches at each vertex, as compressed lists (a counting sort by vertex).
  std::vector<uint32_t> start(mesh.vertices().size() + 1, 0);
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    const PatchNode& node = mesh.nodeOf(p);
    for (int k = 0; k < node.cornerCount(); ++k) ++start[node.corners[k] + 1];
  }
  for (size_t v = 1; v < start.size(); ++v) start[v] += start[v - 1];
  std::vector<uint32_t> at(start.back()), fill(start.begin(), start.end() - 1);
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    const PatchNode& node = mesh.nodeOf(p);
    for (int k = 0; k < node.cornerCount(); ++k) at[fill[node.corners[k]]++] = p;
  }
  for (size_t v = 0; v + 1 < start.size(); ++v)
    for (uint32_t i = start[v]; i < start[v + 1]; ++i)
      for (uint32_t j = i + 1; j < start[v + 1]; ++j) f(at[i], at[j]);
}

}  // namespace

std::vector<uint8_t> PatchLightCache::update(std::span<const Light> lights) {
  std::vector<uint8_t> changed(lights.size(), 1);
  if (lights.size() != lights_.size()) {
    byLight_.assign(lights.size(), {});
  } else {
    for (size_t l = 0; l < lights.size(); ++l) {
      changed[l] = !(lights[l] == lights_[l]);
      if (changed[l]) byLight_[l].clear();
    }
  }
  lights_.assign(lights.begin(), lights.end());
  return changed;
}

const PatchLight* PatchLightCache::find(size_t light, uint64_t address) const {
  const auto it = byLight_[light].find(address);
  return it == byLight_[light].end() ? nullptr : &it->second;
}

void PatchLightCache::insert(size_t light, uint64_t address, const PatchLight& value) {
  byLight_[light][address] = value;
}

std::vector<Color> PatchLightCache::directOf(const PatchMesh& mesh,
                                             std::span<const uint32_t> lights) const {
  std::vector<Color> direct(mesh.size(), Color(0.0f));
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    const uint64_t address = mesh.nodeAddress(mesh.patches()[p].node);
    for (uint32_t l : lights) direct[p] += find(l, address)->direct;
  }
  return direct;
}

namespace {

// Every light's value on every patch, from the cache or evaluated now (in parallel) and cached.
std::vector<PatchLight> lightPatches(const PatchMesh& mesh, const DirectLighting& direct,
                                     int samples, PatchLightCache& cache) {
  const std::span<const Light> lights = direct.lights();
  std::vector<uint64_t> address(mesh.size());
  std::vector<std::pair<uint32_t, uint32_t>> todo;  // (patch, light)
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    address[p] = mesh.nodeAddress(mesh.patches()[p].node);
    for (uint32_t l = 0; l < lights.size(); ++l)
      if (!cache.find(l, address[p])) todo.emplace_back(p, l);
  }
  std::vector<PatchLight> fresh(todo.size());
  tbb::parallel_for(size_t(0), todo.size(), [&](size_t i) {
    fresh[i] = lightOnPatch(mesh, todo[i].first, direct, lights[todo[i].second], samples);
  });
  for (size_t i = 0; i < todo.size(); ++i)
    cache.insert(todo[i].second, address[todo[i].first], fresh[i]);
  std::vector<PatchLight> total(mesh.size());
  for (uint32_t p = 0; p < mesh.size(); ++p)
    for (uint32_t l = 0; l < lights.size(); ++l) total[p] += *cache.find(l, address[p]);
  return total;
}

// The patches to split: crossed by an edge of some light's light, or differing too much from a
// neighbour, and not yet at the finest level.
std::vector<uint32_t> patchesToSplit(const PatchMesh& mesh, const std::vector<PatchLight>& light,
                                     const LightRefinementSettings& settings) {
  std::vector<uint8_t> split(mesh.size(), 0);
  for (uint32_t p = 0; p < mesh.size(); ++p) split[p] = light[p].edgeInside;
  float brightest = 0.0f;
  for (uint32_t p = 0; p < mesh.size(); ++p)
    brightest = std::max(brightest, luminance(light[p].direct));
  forEachNeighbourPair(mesh, [&](uint32_t a, uint32_t b) {
    const float da = luminance(light[a].direct), db = luminance(light[b].direct);
    const float larger = std::max(da, db);
    // Below a thousandth of the brightest patch, differences are not worth patches.
    if (larger > 1e-3f * brightest && std::abs(da - db) > settings.threshold * larger)
      split[a] = split[b] = 1;
  });
  std::vector<uint32_t> chosen;
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    const PatchNode& node = mesh.nodeOf(p);
    if (split[p] && node.depth < mesh.roots()[node.root].baseDepth + settings.levels)
      chosen.push_back(p);
  }
  return chosen;
}

}  // namespace

LightRefinement refineForLights(PatchMesh& mesh, const DirectLighting& direct,
                                const LightRefinementSettings& settings, PatchLightCache& cache,
                                const ProgressCallback& progress) {
  LightRefinement out;
  out.basePatches = mesh.size();
  if (!direct.hasLights()) return out;
  ProgressTicker ticker(progress, size_t(settings.levels) + 1);
  for (;;) {
    const std::vector<PatchLight> light = lightPatches(mesh, direct, settings.samples, cache);
    ticker.tick();
    ticker.throwIfCancelled();
    const std::vector<uint32_t> chosen = patchesToSplit(mesh, light, settings);
    const size_t before = mesh.size();
    if (!chosen.empty()) mesh.refine(chosen);
    if (mesh.size() == before) {
      out.direct.resize(mesh.size());
      for (uint32_t p = 0; p < mesh.size(); ++p) out.direct[p] = light[p].direct;
      return out;
    }
    out.split += chosen.size();
    ++out.rounds;
  }
}

LightRefinement refineForLights(PatchMesh& mesh, const DirectLighting& direct,
                                const LightRefinementSettings& settings,
                                const ProgressCallback& progress) {
  PatchLightCache cache;
  cache.update(direct.lights());
  return refineForLights(mesh, direct, settings, cache, progress);
}

}  // namespace rad
