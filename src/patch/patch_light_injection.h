#pragma once
// The analytic lights' share of the patch method: point, spot and IES lights have no area, so
// they take no part in form factors; their direct irradiance on each patch enters the system as
// D (PatchSystem), a first shot that the solvers then bounce.

#include <radiosity/progress.h>

#include <vector>

#include "lighting/direct_lighting.h"
#include "patch/patch_mesh.h"

namespace rad {

/// Direct irradiance from the scene's analytic lights on every patch: the area mean over the
/// midpoint rule's points (`points` per patch, rounded up to a square), each seen from every
/// light through one shadow ray, so that a beam or shadow edge crossing a patch gives it the
/// share of light that falls on it (never the centroid's all or nothing). Empty when the scene
/// has no lights. Throws rad::Cancelled if `progress` returns false.
std::vector<Color> patchLightIrradiance(const PatchMesh& mesh, const DirectLighting& direct,
                                        int points, const ProgressCallback& progress = {});

}  // namespace rad
