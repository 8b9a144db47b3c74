#pragma once
// The form-factor table on disk, so that a second run on the same geometry with the same meshing
// and estimator settings loads it instead of casting rays. The file holds a magic, a format
// version, the key it was computed for, the table and a checksum of all of it; it is written
// atomically (core/atomic_file.h). A file that is truncated, corrupt, of another version or for
// another key is never used: the loader says why in one warning and the caller recomputes.

#include <radiosity/scene.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "patch/form_factor_estimators.h"
#include "patch/form_factor_table.h"

namespace rad {

struct FormFactorCacheKey {
  uint64_t high = 0, low = 0;
  std::string hex() const;
  bool operator==(const FormFactorCacheKey&) const = default;
};

/// A hash of what the table depends on: the scene's positions, triangles, faces and sidedness,
/// which faces emit, the mesh (its patch size and which quadtree nodes are its patches: adaptive
/// subdivision makes them depend on the lights), the estimator settings (the estimator decides
/// whether rows are symmetrized) and the threshold (not the materials' colours, so that
/// repainting a scene reuses its table).
FormFactorCacheKey formFactorCacheKey(const Scene& scene, const PatchMesh& mesh,
                                      const FormFactorSettings& settings, float threshold);

/// $XDG_CACHE_HOME/radiosity, else $HOME/.cache/radiosity, else "" (no cache).
std::filesystem::path defaultFormFactorCacheDir();
/// The file for a key inside the cache directory.
std::filesystem::path formFactorCacheFile(const std::filesystem::path& dir,
                                          const FormFactorCacheKey& key);

struct FormFactorCacheLoad {
  std::optional<FormFactorTable> table;
  std::string warning;  ///< why an existing file was not used; empty if none or it was used
};

/// Reads the table for `key` with `patches` rows; a missing file is no warning. Never throws for
/// a bad file.
FormFactorCacheLoad loadFormFactorTable(const std::filesystem::path& file,
                                        const FormFactorCacheKey& key, size_t patches);
/// Writes the table (creating the directory); returns a warning instead of throwing on failure.
std::string saveFormFactorTable(const std::filesystem::path& file, const FormFactorCacheKey& key,
                                const FormFactorTable& table);

}  // namespace rad
