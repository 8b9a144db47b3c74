// The patch method as a RadiosityMethod: its settings (the "Patch method" group of --help and
// the scene's "solver" keys), PatchModel as its model, the Relighter as its relighting.
#include "patch/patch_method.h"

#include <radiosity/patch_radiosity.h>
#include <radiosity/relighter.h>

#include <limits>

#include "scene/setting_fields.h"

namespace rad {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
const std::string kGroup = "Patch method";

std::vector<SettingDeclaration> patchSettingDeclarations() {
  using P = PatchRadiositySettings;
  std::vector<SettingDeclaration> d;
  d.push_back(sectionField("patch_size", kGroup, &P::patchSize,
                           "Longest patch edge in scene units (the base level)",
                           {0, kInfinity, true}));
  d.back().defaultText = "from --patches";
  d.push_back(sectionField(
      "patches", kGroup, &P::targetPatches,
      "Approximate number of patches (the base level) beyond the one each face is at least",
      {1, 4294967296.0}));
  d.push_back(sectionChoice("ff_estimator", kGroup, &P::estimator, kFormFactorEstimatorNames,
                            "Form factors by: hemisphere (rays from each patch), pairwise (point "
                            "pairs), exact (point-to-polygon, visibility rays)"));
  d.push_back(sectionField("ff_rays", kGroup, &P::formFactorRays,
                           "Rays per patch (hemisphere), point pairs per patch pair (pairwise) or "
                           "points per patch (exact)",
                           {1, 1 << 24}));
  d.push_back(sectionField("ff_threshold", kGroup, &P::formFactorThreshold,
                           "Drop form factors below this, passing their light to the patch's "
                           "largest",
                           {0, 1, false, true}));
  d.push_back(sectionChoice("solver", kGroup, &P::solver, kPatchSolverNames, "Linear solver"));
  d.push_back(sectionField("max_iterations", kGroup, &P::maxIterations,
                           "Solver sweeps at most (progressive: shots / patches)", {1, 1e8}));
  d.push_back(sectionChoice("shading", kGroup, &P::shading, kPatchShadingNames,
                            "Rendering of the patches"));
  d.push_back(sectionField("light_samples", kGroup, &P::lightSamples,
                           "Points per patch (rounded up to a square) at which point, spot and "
                           "IES light is averaged",
                           {1, 1 << 16}));
  d.push_back(sectionField("refine_levels", kGroup, &P::refineLevels,
                           "Adaptive subdivision for point, spot and IES lights: levels below the "
                           "base patch size at most (0: none)",
                           {0, 8}));
  d.push_back(sectionField("refine_threshold", kGroup, &P::refineThreshold,
                           "Split neighbouring patches whose direct light differs by more than "
                           "this, relative",
                           {0, kInfinity, true}));
  return d;
}

// The patch settings a run resolved: the method's section with the general settings in it.
PatchRadiositySettings patchSettingsOf(const MethodSettings& m) {
  PatchRadiositySettings s = m.section<PatchRadiositySettings>();
  s.seed = m.seed;
  s.tolerance = m.tolerance;
  s.cacheDir = m.cacheDir;
  s.lightGroups = m.lightGroups;
  s.processes = m.processes;
  return s;
}

class PatchMethodModel final : public MethodModel {
 public:
  PatchMethodModel(const Scene& scene, const RayCaster& caster, const MethodSettings& settings)
      : model_(scene, caster, patchSettingsOf(settings)) {}

  std::string solveLabel() const override { return "patch solve"; }

  std::unique_ptr<SurfaceSolution> solve(std::span<const Light> lights,
                                         const RayCaster* shadowCaster,
                                         const ProgressCallback& progress) const override {
    return std::make_unique<PatchRadiosity>(shadowCaster
                                                ? model_.solve(lights, *shadowCaster, progress)
                                                : model_.solve(lights, progress));
  }

  std::unique_ptr<SurfaceSolution> load(const std::string& path,
                                        std::span<const Light> lights) const override {
    return std::make_unique<PatchRadiosity>(model_.load(path, lights));
  }

  std::unique_ptr<Relighting> startRelighting(std::span<const Light> lights,
                                              const std::string& solutionFile,
                                              const RelightSettings& settings,
                                              const ProgressCallback& progress) const override {
    if (solutionFile.empty())
      return std::make_unique<Relighter>(model_, lights, settings, progress);
    return std::make_unique<Relighter>(model_, model_.load(solutionFile, lights), settings,
                                       progress);
  }

 private:
  PatchModel model_;
};

class PatchMethod final : public RadiosityMethod {
 public:
  std::string name() const override { return "patch"; }
  std::string settingsGroup() const override { return kGroup; }
  MethodCapabilities capabilities() const override {
    MethodCapabilities c;
    c.relight = c.saveSolution = c.lightGroups = c.processes = true;
    return c;
  }
  std::vector<SettingDeclaration> settingDeclarations() const override {
    return patchSettingDeclarations();
  }
  std::unique_ptr<MethodModel> prepare(const Scene& scene, const RayCaster& caster,
                                       const MethodSettings& settings) const override {
    return std::make_unique<PatchMethodModel>(scene, caster, settings);
  }
};

}  // namespace

std::unique_ptr<RadiosityMethod> makePatchMethod() {
  return std::make_unique<PatchMethod>();
}

}  // namespace rad
