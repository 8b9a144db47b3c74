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

#include <vector>

#include "lighting/direct_lighting.h"
#include "patch/patch_mesh.h"

namespace rad {

struct LightRefinementSettings {
  int levels = 2;          ///< finest level: this many levels below the base patch size
  float threshold = 0.5f;  ///< relative difference of neighbours' direct light that splits them
  int samples = 16;        ///< points per patch (rounded up to a square) for D and the edges
};

struct LightRefinement {
  std::vector<Color> direct;  ///< D per patch of the refined mesh (patchLightIrradiance's mean)
  size_t basePatches = 0;     ///< patches before refinement
  size_t split = 0;           ///< patches split, over all rounds
  int rounds = 0;             ///< rounds that split something
};

/// Refines `mesh` for the scene's analytic lights and returns their direct light on each patch
/// of the result. With no lights or `levels` 0 the mesh stays as it is. Throws rad::Cancelled if
/// `progress` returns false.
LightRefinement refineForLights(PatchMesh& mesh, const DirectLighting& direct,
                                const LightRefinementSettings& settings,
                                const ProgressCallback& progress = {});

}  // namespace rad
