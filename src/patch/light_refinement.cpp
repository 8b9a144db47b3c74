#include "patch/light_refinement.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <unordered_map>

#include "patch/patch_light_injection.h"
#include "render/progress_ticker.h"

namespace rad {

namespace {

// Patches that share a corner, each pair once (i < j).
std::vector<std::pair<uint32_t, uint32_t>> neighbourPairs(const PatchMesh& mesh) {
  std::unordered_map<uint32_t, std::vector<uint32_t>> byVertex;
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    const PatchNode& node = mesh.nodeOf(p);
    for (int k = 0; k < node.cornerCount(); ++k) byVertex[node.corners[k]].push_back(p);
  }
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  for (const auto& [vertex, patches] : byVertex)
    for (size_t a = 0; a < patches.size(); ++a)
      for (size_t b = a + 1; b < patches.size(); ++b)
        pairs.push_back(std::minmax(patches[a], patches[b]));
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

}  // namespace

LightRefinement refineForLights(PatchMesh& mesh, const DirectLighting& direct,
                                const LightRefinementSettings& settings,
                                const ProgressCallback& progress) {
  LightRefinement out;
  out.basePatches = mesh.size();
  if (!direct.hasLights()) return out;
  std::unordered_map<uint32_t, PatchLight> byNode;  // leaves already evaluated, by node id
  ProgressTicker ticker(progress, size_t(settings.levels) + 1);
  for (;;) {
    std::vector<uint32_t> todo;
    for (uint32_t p = 0; p < mesh.size(); ++p)
      if (!byNode.contains(mesh.patches()[p].node)) todo.push_back(p);
    std::vector<PatchLight> fresh(todo.size());
    tbb::parallel_for(size_t(0), todo.size(), [&](size_t i) {
      fresh[i] = lightOnPatch(mesh, todo[i], direct, settings.samples);
    });
    for (size_t i = 0; i < todo.size(); ++i) byNode[mesh.patches()[todo[i]].node] = fresh[i];
    ticker.tick();
    ticker.throwIfCancelled();

    auto at = [&](uint32_t p) -> const PatchLight& { return byNode.at(mesh.patches()[p].node); };
    std::vector<uint8_t> split(mesh.size(), 0);
    for (uint32_t p = 0; p < mesh.size(); ++p) split[p] = at(p).edgeInside;
    float brightest = 0.0f;
    for (uint32_t p = 0; p < mesh.size(); ++p)
      brightest = std::max(brightest, luminance(at(p).direct));
    for (const auto& [a, b] : neighbourPairs(mesh)) {
      const float da = luminance(at(a).direct), db = luminance(at(b).direct);
      const float larger = std::max(da, db);
      // Below a thousandth of the brightest patch, differences are not worth patches.
      if (larger > 1e-3f * brightest && std::abs(da - db) > settings.threshold * larger)
        split[a] = split[b] = 1;
    }
    std::vector<uint32_t> chosen;
    for (uint32_t p = 0; p < mesh.size(); ++p) {
      const PatchNode& node = mesh.nodeOf(p);
      if (split[p] && node.depth < mesh.roots()[node.root].baseDepth + settings.levels)
        chosen.push_back(p);
    }
    const size_t before = mesh.size();
    if (!chosen.empty()) mesh.refine(chosen);
    if (mesh.size() == before) break;
    out.split += chosen.size();
    ++out.rounds;
  }
  out.direct.resize(mesh.size());
  for (uint32_t p = 0; p < mesh.size(); ++p)
    out.direct[p] = byNode.at(mesh.patches()[p].node).direct;
  return out;
}

}  // namespace rad
