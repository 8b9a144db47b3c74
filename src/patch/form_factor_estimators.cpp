// The choice among the form-factor estimators of form_factor_estimators.h.
#include "patch/form_factor_estimators.h"

namespace rad {

FormFactorRows estimateFormFactors(const PatchMesh& mesh, const RayCaster& caster,
                                   const FormFactorSettings& settings,
                                   const ProgressCallback& progress) {
  switch (settings.estimator) {
    case FormFactorEstimator::Hemisphere:
      return hemisphereFormFactors(mesh, caster, settings, progress);
    case FormFactorEstimator::Pairwise:
      return pairwiseFormFactors(mesh, caster, settings, progress);
    case FormFactorEstimator::Exact:
      break;
  }
  return exactFormFactors(mesh, caster, settings, progress);
}

}  // namespace rad
