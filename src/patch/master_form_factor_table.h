#pragma once
// The form factors of every quadtree node ever solved, kept by node: what lets a light move
// without recomputing the scene's form factors. A node's row is its hemisphere rays' hits, each
// by where it landed in the quadtree as deep as refinement may go (PatchMesh::finestKey), so one
// row serves any set of patches: the hits that land inside a patch, whatever its depth, are the
// ones its node's key range holds. When the patches change, only the rows of nodes never
// computed before are cast. The disk cache stores this table, keyed by the geometry and the base
// meshing, not by the lights.

#include <radiosity/progress.h>
#include <radiosity/ray_caster.h>

#include <cstdint>
#include <filesystem>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "patch/form_factor_cache.h"
#include "patch/form_factor_estimators.h"
#include "patch/patch_mesh.h"

namespace rad {

class MasterFormFactorTable {
 public:
  /// `levels`: how far below the base patch size refinement may go (the keys' depth); `rays`,
  /// `seed`: the hemisphere estimator's.
  MasterFormFactorTable(int levels, int rays, uint64_t seed);

  /// The rows of `mesh`'s patches, as hemisphereFormFactors makes them (the same numbers for
  /// the same patches), with the exact columns of ff.exactColumns (the emitters) in place. A
  /// node's rays come from the stream of its base patch (`basePatchOf[node]`, from the model's
  /// base mesh) or, for a node that refinement made, one of its own. Rows of nodes kept from
  /// before are not cast again, nor their exact entries while the emitter nodes are the same.
  /// Thread-safe. Throws rad::Cancelled if `progress` returns false.
  /// `wanted`: per patch, whether its row is made (empty: all); the others' rows stay empty
  /// and are not cast.
  struct Rows {
    FormFactorRows rows;
    size_t computed = 0, reused = 0;  ///< rows cast now (hemisphere or exact part), rows kept
    /// The exact columns (ff.exactColumns), when there are any.
    std::optional<ExactColumns> exact;
    /// Per patch, its rays' hits sorted by key (null for an exact patch, or one not wanted and
    /// never cast); they stay valid as long as the table.
    std::vector<const std::vector<HemisphereHit>*> hits;
  };
  Rows rowsFor(const PatchMesh& mesh, const RayCaster& caster,
               const std::vector<uint32_t>& basePatchOf, const FormFactorSettings& ff,
               const ProgressCallback& progress, std::span<const uint8_t> wanted = {});
  /// The finest-key depth below the base patches (the constructor's `levels`).
  int levels() const { return levels_; }

  /// Node rows kept.
  size_t rows() const;
  size_t memoryBytes() const;

  /// Reads the rows of `file` if it holds this key's table (masterTableCacheKey), keeping them
  /// with those computed since; a bad file is a warning (returned) and nothing read.
  std::string load(const std::filesystem::path& file, const FormFactorCacheKey& key);
  /// Writes every row (atomically); a failure is a warning (returned).
  std::string save(const std::filesystem::path& file, const FormFactorCacheKey& key) const;
  /// Where rowsFor keeps the rows while it casts them (every checkpointIntervalSeconds, and
  /// when stopped), so that a solve killed or stopped part way casts only the rest when run
  /// again. Not called: nowhere.
  void keepOnDisk(const std::filesystem::path& file, const FormFactorCacheKey& key);

 private:
  int levels_, rays_;
  uint64_t seed_;
  mutable std::mutex mutex_;
  MasterRows rows_;
  // memoryBytes(), kept as rows change (a relighter asks at every change of the quadtree).
  size_t bytes_ = 0;
  static size_t rowBytes(const MasterRow& row);
  // The row at `address` (made if new) changed by `change(row)`, under the lock.
  template <class Change>
  void changeRow(uint64_t address, const Change& change) {
    const auto [it, inserted] = rows_.try_emplace(address);
    if (!inserted) bytes_ -= rowBytes(it->second);
    change(it->second);
    bytes_ += rowBytes(it->second);
  }
  std::filesystem::path diskFile_;
  FormFactorCacheKey diskKey_;
};

}  // namespace rad
