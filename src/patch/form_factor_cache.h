#pragma once
// The form-factor table on disk, so that a second run on the same geometry with the same meshing
// and estimator settings loads it instead of casting rays. The file holds a magic, a format
// version, the key it was computed for, the table and a checksum of all of it; it is written
// atomically (radiosity/atomic_file.h). A file that is truncated, corrupt, of another version or
// for another key is never used: the loader says why in one warning and the caller recomputes.

#include <radiosity/scene.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <unordered_map>

#include "core/binary_io.h"
#include "patch/form_factor_estimators.h"
#include "patch/form_factor_table.h"

namespace rad {

using FormFactorCacheKey = Key128;

/// A hash of what the table depends on: the scene's positions, triangles, faces and sidedness,
/// which faces emit, the mesh (its patch size and which quadtree nodes are its patches: adaptive
/// subdivision makes them depend on the lights), the estimator settings (the estimator decides
/// whether rows are symmetrized) and the threshold (not the materials' colours, so that
/// repainting a scene reuses its table).
FormFactorCacheKey formFactorCacheKey(const Scene& scene, const PatchMesh& mesh,
                                      const FormFactorSettings& settings, float threshold);

/// One node's row of the master table (MasterFormFactorTable): its hemisphere rays' hits, and its
/// exact entries for the emitters (key: the emitter node's address, weight: F), computed against
/// the emitter nodes whose addresses hash to exactSet.
struct MasterRow {
  std::vector<HemisphereHit> hits, exact;
  uint64_t exactSet = 0;
  bool hasHits = false;   ///< the rays were cast (a row may find nothing)
  bool hasExact = false;  ///< the exact entries were computed (for exactSet)
};
/// The master table's rows by node address (PatchMesh::nodeAddress).
using MasterRows = std::unordered_map<uint64_t, MasterRow>;
/// What the master table depends on: the scene's positions, triangles, faces and sidedness, the
/// base mesh's patch size, the refinement levels (the depth of its keys), rays and seed. Not the
/// lights, the materials or the threshold: every solve of the geometry shares it.
FormFactorCacheKey masterTableCacheKey(const Scene& scene, const PatchMesh& baseMesh, int levels,
                                       int rays, uint64_t seed);
std::filesystem::path masterTableCacheFile(const std::filesystem::path& dir,
                                           const FormFactorCacheKey& key);
struct MasterRowsLoad {
  std::optional<MasterRows> rows;
  std::string warning;  ///< why an existing file was not used; empty if none or it was used
};
MasterRowsLoad loadMasterRows(const std::filesystem::path& file, const FormFactorCacheKey& key);
/// Writes the rows atomically; returns a warning if that failed.
std::string saveMasterRows(const std::filesystem::path& file, const FormFactorCacheKey& key,
                           const MasterRows& rows);

/// $XDG_CACHE_HOME/radiosity, else $HOME/.cache/radiosity, else "" (no cache).
std::filesystem::path defaultFormFactorCacheDir();
/// The file for a key inside the cache directory.
std::filesystem::path formFactorCacheFile(const std::filesystem::path& dir,
                                          const FormFactorCacheKey& key);

/// The largest row sum a cached table may have: 1 plus the estimators' noise (the exact
/// estimator's point-to-polygon formula overshoots for patches large against their distance).
constexpr double kMaxCachedRowSum = 1.5;

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
