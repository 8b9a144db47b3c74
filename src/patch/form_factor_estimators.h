#pragma once
// The three ways to estimate the form factors between patches. Each returns one row of
// (column, F) entries per patch, sorted by column with each column once, for
// FormFactorTable::fromRows.
//   hemisphere: rays from stratified points on patch i in stratified cosine-weighted directions;
//               the fraction landing on each patch j is F_ij (cost: patches x rays).
//   pairwise:   for each facing pair, random point pairs averaging cos cos / (pi r^2) times
//               visibility; one geometric term serves both F_ij and F_ji (cost: patches^2 x pairs).
//   exact:      the exact unoccluded point-to-polygon factor at points of patch i, times the
//               visibility of patch j from each point by a sample ray (cost: patches^2 x points).

#include <radiosity/patch_radiosity.h>
#include <radiosity/progress.h>

#include <cstdint>
#include <vector>

#include "geometry/ray_caster.h"
#include "patch/form_factor_table.h"
#include "patch/patch_mesh.h"

namespace rad {

using FormFactorEstimator = PatchFormFactorEstimator;

struct FormFactorSettings {
  FormFactorEstimator estimator = FormFactorEstimator::Hemisphere;
  /// hemisphere: rays per patch (rounded up to a square); pairwise: point pairs per patch pair;
  /// exact: points per patch (rounded up to a square), each with one visibility ray per patch.
  int rays = 256;
  uint64_t seed = 1;
};

using FormFactorRows = std::vector<std::vector<FormFactorEntry>>;

/// One row by hemisphere ray casting (entries merged by column). Thread-safe.
std::vector<FormFactorEntry> hemisphereRow(const PatchMesh& mesh, const RayCaster& caster,
                                           uint32_t patch, int rays, uint64_t seed);

/// Every row by settings.estimator, the one place that maps the kind to its estimator (below).
/// Throws rad::Cancelled if `progress` returns false.
FormFactorRows estimateFormFactors(const PatchMesh& mesh, const RayCaster& caster,
                                   const FormFactorSettings& settings,
                                   const ProgressCallback& progress);

/// Every row by one estimator, whatever settings.estimator says. Throws rad::Cancelled if
/// `progress` returns false.
FormFactorRows hemisphereFormFactors(const PatchMesh& mesh, const RayCaster& caster,
                                     const FormFactorSettings& settings,
                                     const ProgressCallback& progress);
FormFactorRows pairwiseFormFactors(const PatchMesh& mesh, const RayCaster& caster,
                                   const FormFactorSettings& settings,
                                   const ProgressCallback& progress);
FormFactorRows exactFormFactors(const PatchMesh& mesh, const RayCaster& caster,
                                const FormFactorSettings& settings,
                                const ProgressCallback& progress);

}  // namespace rad
