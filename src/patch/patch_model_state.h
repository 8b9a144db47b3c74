#pragma once
// What a PatchModel shares with its solutions: the scene, the ray caster, the settings, the base
// mesh, and the form-factor tables of the last patch sets solved.

#include <radiosity/patch_radiosity.h>

#include <deque>
#include <memory>
#include <mutex>

#include "patch/form_factor_cache.h"
#include "patch/form_factor_table.h"
#include "patch/patch_mesh.h"

namespace rad {

struct PatchModel::State {
  const Scene* scene = nullptr;
  const RayCaster* caster = nullptr;
  std::unique_ptr<RayCaster> ownCaster;  ///< when the model was given none
  PatchRadiositySettings settings;
  std::unique_ptr<PatchMesh> baseMesh;
  double meshSeconds = 0.0;

  /// The table of a patch set solved before (keyed as the disk cache keys it), or null.
  std::shared_ptr<const FormFactorTable> keptTable(const FormFactorCacheKey& key) const;
  /// Keeps `table` for later solves, the oldest of more than kKeptTables going.
  void keep(const FormFactorCacheKey& key, std::shared_ptr<const FormFactorTable> table) const;

 private:
  static constexpr size_t kKeptTables = 2;
  mutable std::mutex mutex_;
  mutable std::deque<std::pair<FormFactorCacheKey, std::shared_ptr<const FormFactorTable>>> kept_;
};

}  // namespace rad
