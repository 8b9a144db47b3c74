#pragma once
// Adaptive subdivision of the patch mesh along the edges of the analytic lights' light: a patch
// is split where a spot's or IES light's beam edge crosses it (some of its points inside the
// beam, some outside), where a shadow boundary crosses it (some points see the light, some do
// not), or where its direct irradiance differs from a neighbour's by more than a threshold,
// until no patch qualifies or the finest level is reached. Light-driven meshing as in D.
// Lischinski, F. Tampieri and D. Greenberg, "Discontinuity meshing for accurate radiosity", IEEE
// CG&A 1992 (which places the edges exactly; here the quadtree only brackets them) and the
// adaptive subdivision of M. Cohen and J. Wallace, "Radiosity and Realistic Image Synthesis"
// (1993), chapter 8.

#include <radiosity/progress.h>

#include <span>
#include <unordered_map>
#include <vector>

#include "lighting/direct_lighting.h"
#include "patch/patch_light_injection.h"
#include "patch/patch_mesh.h"

namespace rad {

struct LightRefinementSettings {
  int levels = 2;          ///< finest level: this many levels below the base patch size
  float threshold = 0.5f;  ///< relative difference of neighbours' direct light that splits them
  int samples = 16;        ///< points per patch (rounded up to a square) for D and the edges
};

struct LightRefinement {
  std::vector<Color> direct;  ///< D per patch of the refined mesh (lightOnPatch's)
  size_t basePatches = 0;     ///< patches before refinement
  size_t split = 0;           ///< patches split, over all rounds
  int rounds = 0;             ///< rounds that split something
};

/// What each analytic light puts on each quadtree node evaluated so far, by node address
/// (PatchMesh::nodeAddress, the same in every mesh refined from one base mesh): what lets the
/// patches be lit again for moved lights by evaluating only the lights that moved.
class PatchLightCache {
 public:
  /// Keeps what it holds of the lights equal to `lights` (by position in the list), forgets the
  /// rest, and returns per light whether it changed (all, when the count did).
  std::vector<uint8_t> update(std::span<const Light> lights);
  /// Forgets every value (what shadows the lights changed: objects moved).
  void forget() {
    lights_.clear();
    byLight_.clear();
  }
  /// What light `light` puts on the node at `address`, if evaluated.
  const PatchLight* find(size_t light, uint64_t address) const;
  void insert(size_t light, uint64_t address, const PatchLight& value);
  /// The direct light of the lights `lights` (indices) on each patch of `mesh`, which it must
  /// hold (the mesh refined with it): one light group's D.
  std::vector<Color> directOf(const PatchMesh& mesh, std::span<const uint32_t> lights) const;

 private:
  std::vector<Light> lights_;
  std::vector<std::unordered_map<uint64_t, PatchLight>> byLight_;
};

/// Refines `mesh` for the analytic lights of `direct` and returns their direct light on each
/// patch of the result (the sum of each light's lightOnPatch, in their order). With no lights or
/// `levels` 0 the mesh stays as it is. The lights' values on nodes come from `cache` where it
/// has them (it must have been updated with the same lights), and are added to it. Throws
/// rad::Cancelled if `progress` returns false.
LightRefinement refineForLights(PatchMesh& mesh, const DirectLighting& direct,
                                const LightRefinementSettings& settings, PatchLightCache& cache,
                                const ProgressCallback& progress = {});
/// The same with a cache of its own.
LightRefinement refineForLights(PatchMesh& mesh, const DirectLighting& direct,
                                const LightRefinementSettings& settings,
                                const ProgressCallback& progress = {});

}  // namespace rad
