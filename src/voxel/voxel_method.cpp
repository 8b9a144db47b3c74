// The voxel method as a RadiosityMethod: its settings (the "Voxel method" group of --help and the
// scene's "solver" keys) and VoxelModel as its model.
#include "voxel/voxel_method.h"

#include <fmt/format.h>
#include <radiosity/voxel_radiosity.h>

#include <limits>

#include "scene/setting_fields.h"

namespace rad {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
const std::string kGroup = "Voxel method";

std::vector<SettingDeclaration> voxelSettingDeclarations() {
  using V = VoxelRadiositySettings;
  std::vector<SettingDeclaration> d;
  d.push_back(sectionField("voxel_size", kGroup, &V::voxelSize, "Voxel edge in scene units",
                           {0, kInfinity, true}));
  d.back().defaultText = "from --voxels";
  d.push_back(sectionField("voxels", kGroup, &V::targetVoxels,
                           "Approximate number of surface voxels", {1, 4294967296.0}));
  d.push_back(sectionField("sphere_radius", kGroup, &V::sphereRadius,
                           "Radius R of the discrete sphere of directions (38: 14,790 directions)",
                           {1, 200}));
  d.push_back(sectionField("later_sphere_radius", kGroup, &V::laterSphereRadius,
                           "Sphere radius for the sweeps after the first, whose light is smoother",
                           {1, 200}));
  d.back().defaultText = "--sphere-radius";
  d.push_back(sectionField("iterations", kGroup, &V::iterations,
                           "Sweeps over all directions at most, before --tolerance is reached "
                           "(all of them with --tolerance 0)",
                           {1, 100000}));
  d.push_back(sectionField("tangent_correction", kGroup, &V::tangentCorrection,
                           "Look through voxels a line only grazes"));
  d.push_back(sectionField("first_shot", kGroup, &V::directFirstShot,
                           "Direct light by shadow rays before the sweeps"));
  d.push_back(sectionField("direct_samples", kGroup, &V::directSamples,
                           "Shadow-ray samples of the emitting surfaces per voxel side for the "
                           "first shot",
                           {1, 1 << 20}));
  d.push_back(sectionField("normalize", kGroup, &V::normalize,
                           "Per-voxel normalization of the direction factors"));
  d.push_back(sectionField("jitter_lines", kGroup, &V::jitterLines,
                           "Shift each direction's lines every iteration"));
  d.push_back(sectionField("tail_estimate", kGroup, &V::estimateTail,
                           "Add the bounces after the last iteration, extrapolated"));
  return d;
}

// The voxel settings a run resolved: the method's section with the general settings in it.
VoxelRadiositySettings voxelSettingsOf(const MethodSettings& m) {
  VoxelRadiositySettings s = m.section<VoxelRadiositySettings>();
  s.seed = m.seed;
  s.tolerance = m.tolerance;
  s.checkpointDir = m.cacheDir;
  s.lightGroups = m.lightGroups;
  s.keepDirectLight = m.keepDirectLight;
  s.processes = m.processes;
  return s;
}

class VoxelMethodModel final : public MethodModel {
 public:
  VoxelMethodModel(const Scene& scene, const RayCaster& caster, const MethodSettings& settings)
      : settings_(voxelSettingsOf(settings)), model_(scene, caster, settings_) {}

  // What ends the solve, so that the time left reads against it.
  std::string solveLabel() const override {
    if (settings_.tolerance > 0.0)
      return fmt::format("voxel solve (to {:g} of the light still bouncing, {} iterations at most)",
                         settings_.tolerance, settings_.iterations);
    return fmt::format("voxel solve ({} iterations)", settings_.iterations);
  }

  std::unique_ptr<SurfaceSolution> solve(std::span<const Light> lights,
                                         const RayCaster* shadowCaster,
                                         const ProgressCallback& progress) const override {
    return std::make_unique<VoxelRadiosity>(shadowCaster
                                                ? model_.solve(lights, *shadowCaster, progress)
                                                : model_.solve(lights, progress));
  }

  std::unique_ptr<SurfaceSolution> load(const std::string& path,
                                        std::span<const Light> lights) const override {
    return std::make_unique<VoxelRadiosity>(model_.load(path, lights));
  }

 private:
  VoxelRadiositySettings settings_;
  VoxelModel model_;
};

class VoxelMethod final : public RadiosityMethod {
 public:
  std::string name() const override { return "voxel"; }
  std::string settingsGroup() const override { return kGroup; }
  MethodCapabilities capabilities() const override {
    MethodCapabilities c;
    c.saveSolution = c.lightGroups = c.processes = true;
    return c;
  }
  std::vector<SettingDeclaration> settingDeclarations() const override {
    return voxelSettingDeclarations();
  }
  std::unique_ptr<MethodModel> prepare(const Scene& scene, const RayCaster& caster,
                                       const MethodSettings& settings) const override {
    return std::make_unique<VoxelMethodModel>(scene, caster, settings);
  }
};

}  // namespace

std::unique_ptr<RadiosityMethod> makeVoxelMethod() {
  return std::make_unique<VoxelMethod>();
}

}  // namespace rad
