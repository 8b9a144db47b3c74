// A solution file (.rad) with its checksum fixed up, loaded into the patch and the voxel models
// of the scene the seeds were solved for (seed_corpora.cpp).
#include <radiosity/patch_radiosity.h>
#include <radiosity/solution_file.h>
#include <radiosity/voxel_radiosity.h>

#include "fuzz_support.h"

namespace {

const rad::PatchModel& patchModel() {
  static const rad::PatchModel model(rad::fuzz::seedScene(), rad::fuzz::seedPatchSettings(""));
  return model;
}

const rad::VoxelModel& voxelModel() {
  static const rad::VoxelModel model(rad::fuzz::seedScene(), rad::fuzz::seedVoxelSettings());
  return model;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  rad::fuzz::fixChecksum(bytes);
  const std::string file = rad::fuzz::writeInput("solution.rad", bytes);
  const rad::Scene& scene = rad::fuzz::seedScene();
  rad::fuzz::acceptingInputErrors([&] { rad::readSolutionFileInfo(file); });
  rad::fuzz::acceptingInputErrors([&] { patchModel().load(file, scene.lights); });
  rad::fuzz::acceptingInputErrors([&] { voxelModel().load(file, scene.lights); });
  return 0;
}
