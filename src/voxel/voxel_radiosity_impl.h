#pragma once
// What a VoxelModel and a VoxelRadiosity hold, for the code that makes them: the solve and the
// solution file.

#include <radiosity/voxel_radiosity.h>

#include <memory>
#include <span>
#include <vector>

#include "lighting/light_group_mix.h"
#include "voxel/voxel_irradiance_field.h"
#include "voxel/voxel_solver.h"

namespace rad {

class ByteReader;
struct SolutionFile;

struct VoxelModel::State {
  const Scene* scene = nullptr;
  const RayCaster* caster = nullptr;
  std::unique_ptr<RayCaster> ownCaster;  ///< when the model was given none
  VoxelRadiositySettings settings;
  VoxelGrid grid;
  double voxelizeSeconds = 0.0;
};

struct VoxelRadiosity::Impl {
  Impl(std::shared_ptr<const VoxelModel::State> m, std::span<const Light> l)
      : model(std::move(m)), scene(model->scene), grid(model->grid), lights(l.begin(), l.end()) {}
  std::shared_ptr<const VoxelModel::State> model;
  const Scene* scene;
  const VoxelGrid& grid;
  std::vector<Light> lights;  ///< those it is solved with
  /// What shadows the first shot while solving (the scene with its dynamic objects placed);
  /// null: the model's caster.
  const RayCaster* shadowCaster = nullptr;
  VoxelSolution solution;
  std::vector<Color> indirect;  ///< H less the first shot (keepDirectLight); else empty
  VoxelRadiosityStats stats;
  /// The light groups, when solved apart: per group, H and the indirect H per side, which
  /// `solution` and `indirect` combine at the mix's scales.
  LightGroupMix mix;
  std::vector<std::vector<Color>> groupIrradiance, groupIndirect;

  /// Solves for `lights` with `solver`: the solution and the indirect light.
  std::pair<VoxelSolution, std::vector<Color>> solve(std::span<const Light> lights,
                                                     const VoxelSolverSettings& solver,
                                                     const ProgressCallback& progress) const;
  void solveGroups(VoxelSolverSettings solver, const ProgressCallback& progress);
  void combineGroups();
  Color emission(size_t side) const;

  VoxelIrradianceField field() const { return VoxelIrradianceField(grid, solution.irradiance); }
  /// A solution file's payload (voxel_solution_file.cpp).
  void readSolution(const SolutionFile& file, ByteReader in);
};

}  // namespace rad
