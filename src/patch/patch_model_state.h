#pragma once
// What a PatchModel shares with its solutions: the scene, the ray caster, the settings, the base
// mesh, and the master form-factor table.

#include <radiosity/patch_radiosity.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "patch/master_form_factor_table.h"
#include "patch/patch_mesh.h"

namespace rad {

struct PatchModel::State {
  const Scene* scene = nullptr;
  const RayCaster* caster = nullptr;
  std::unique_ptr<RayCaster> ownCaster;  ///< when the model was given none
  PatchRadiositySettings settings;
  std::unique_ptr<PatchMesh> baseMesh;
  std::vector<uint32_t> basePatchOf;  ///< per node of the base mesh: its patch, or kNoPatch
  double meshSeconds = 0.0;
  /// The hemisphere estimator's rows of every node solved so far (and read from the disk
  /// cache, masterFile, when the model was made).
  std::unique_ptr<MasterFormFactorTable> master;
  std::filesystem::path masterFile;
  FormFactorCacheKey masterKey;
  bool masterLoaded = false;  ///< rows came from masterFile
  std::string masterWarning;  ///< why masterFile was not read
};

}  // namespace rad
