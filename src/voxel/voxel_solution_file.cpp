// The voxel method's solution file: per voxel side (the grid is made again from the scene and
// the settings, the same for the same input) the irradiance, and its indirect part where the
// direct light was kept apart, per light group when they were solved apart; the radiosity.
#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/voxel_radiosity.h>

#include "scene/solution_file.h"
#include "voxel/voxel_radiosity_impl.h"

namespace rad {

void VoxelRadiosity::save(const std::string& path, const SolverSettings& settings) const {
  const Impl& m = *impl_;
  std::string out = solutionFileStart("voxel", *m.scene, m.lights, settings);
  put(out, uint64_t(m.grid.entryCount()));
  const bool apart = m.mix.apart();
  put(out, uint8_t(apart));
  put(out, uint8_t(!m.indirect.empty()));
  if (apart) {
    put(out, uint64_t(m.groupIrradiance.size()));
    for (size_t g = 0; g < m.groupIrradiance.size(); ++g) {
      putArray<Color>(out, m.groupIrradiance[g]);
      if (!m.indirect.empty()) putArray<Color>(out, m.groupIndirect[g]);
    }
    putArray<Color>(out, m.mix.scales());
  } else {
    put(out, uint64_t(1));
    putArray<Color>(out, m.solution.irradiance);
    if (!m.indirect.empty()) putArray<Color>(out, m.indirect);
    putArray<Color>(out, m.solution.radiosity);
  }
  writeSolutionFile(path, out);
}

void VoxelRadiosity::Impl::readSolution(const SolutionFile& file, ByteReader in) {
  const uint64_t n = in.get<uint64_t>();
  if (n != grid.entryCount())
    file.refuse(fmt::format("it has {} voxel sides, this scene's grid {}", n, grid.entryCount()));
  const bool apart = in.get<uint8_t>() != 0, hasIndirect = in.get<uint8_t>() != 0;
  mix = LightGroupMix(*scene, lights, apart);
  const uint64_t groups = in.get<uint64_t>();
  if (groups != (apart ? mix.groups().size() : 1))
    file.refuse("it has another number of light groups");
  for (uint64_t g = 0; g < groups; ++g) {
    groupIrradiance.push_back(file.radiometry(in, n, "irradiance"));
    if (hasIndirect) groupIndirect.push_back(file.radiometry(in, n, "indirect irradiance"));
  }
  if (apart) {
    mix.setScales(in.array<Color>(groups));
    combineGroups();
  } else {
    solution.irradiance = std::move(groupIrradiance[0]);
    if (hasIndirect) indirect = std::move(groupIndirect[0]);
    groupIrradiance.clear();
    groupIndirect.clear();
    solution.radiosity = file.radiometry(in, n, "radiosity");
  }
  if (!in.atEnd()) file.refuse("trailing bytes after its arrays");
}

VoxelRadiosity VoxelModel::load(const std::string& path, std::span<const Light> lights) const {
  const SolutionFile file(path);
  file.checkFor("voxel", *state_->scene, lights);
  auto impl = std::make_unique<VoxelRadiosity::Impl>(state_, lights);
  file.readPayload([&](ByteReader in) { impl->readSolution(file, in); });
  VoxelRadiosityStats& s = impl->stats;
  s.voxels = state_->grid.cellCount();
  s.sides = state_->grid.entryCount();
  s.voxelSize = state_->grid.voxelSize;
  s.voxelizeSeconds = state_->voxelizeSeconds;
  return VoxelRadiosity(std::move(impl));
}

}  // namespace rad
