#pragma once
// The analytic lights' share of the patch method: point, spot and IES lights have no area, so
// they take no part in form factors; their direct irradiance on each patch enters the system as
// D (PatchSystem), a first shot that the solvers then bounce.

#include "lighting/direct_lighting.h"
#include "patch/patch_mesh.h"

namespace rad {

/// What a patch receives from analytic lights.
struct PatchLight {
  Color direct{0.0f};       ///< D: the area mean over the midpoint rule's points
  bool edgeInside = false;  ///< some light reaches some of its points and not others

  PatchLight& operator+=(const PatchLight& o) {
    direct += o.direct;
    edgeInside = edgeInside || o.edgeInside;
    return *this;
  }
};
/// What one light puts on a patch: D over the midpoint rule's points (`points`, rounded up to a
/// square), and the edge test over them and the patch's corners (pulled 2% toward its centre, so
/// that an edge along the patch's border is seen too). Nothing, and no rays cast, where the
/// light cannot reach the patch at all (behind its plane, or a spot's cone clear of it). A sky:
/// D by its rays stratified over the points together, no edge test (its light is soft).
/// Thread-safe.
PatchLight lightOnPatch(const PatchMesh& mesh, uint32_t patch, const DirectLighting& direct,
                        const Light& light, int points);
/// The sum of what every light of `direct` puts on the patch, in their order.
PatchLight lightOnPatch(const PatchMesh& mesh, uint32_t patch, const DirectLighting& direct,
                        int points);

}  // namespace rad
