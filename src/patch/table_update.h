#pragma once
// The form-factor table of a quadtree that changed a little (a beam edge moved: some patches
// split, some merged), made from the table before instead of anew. Between two patches both
// meshes hold, the symmetrized entry depends only on their two rows' hits in each other's key
// ranges and on their areas, none of which changed: it is kept. Only the entries that involve a
// patch the new mesh alone holds are computed, from the master table's hits (an unchanged row's
// hits in a new patch's key range; the new patch's own row), and the rows renumbered. The result
// is the table FormFactorTable::symmetrize makes of the new mesh's rows, bit for bit (tested),
// at a cost that follows the changed entries rather than the whole table.

#include <optional>
#include <span>
#include <vector>

#include "patch/form_factor_table.h"
#include "patch/master_form_factor_table.h"
#include "patch/patch_mesh.h"

namespace rad {

/// A table before closure and threshold, and the mesh it is for.
struct SymmetrizedTable {
  const PatchMesh& mesh;
  const FormFactorTable& table;
  /// The patches whose columns were exact (FormFactorSettings::exactColumns), ascending.
  std::span<const uint32_t> exactColumns;
};

/// The patches of two meshes refined from one base mesh, paired by node.
struct PatchMatch {
  std::vector<uint32_t> oldOf;  ///< per new patch, the old one of its node, or kNoPatch
  std::vector<uint32_t> newOf;  ///< per old patch, the new one of its node, or kNoPatch
  /// Per new patch, 1 where the old mesh has no patch of its node (the rows to make).
  std::vector<uint8_t> fresh() const;
};
/// Both meshes are numbered in key order, so one walk pairs the patches of equal key ranges;
/// nullopt when a mesh is not in key order.
std::optional<PatchMatch> matchPatches(const PatchMesh& before, const PatchMesh& mesh, int levels);

/// The symmetrized table of `mesh`, from `before` (a mesh refined from the same base mesh, its
/// patches paired with `mesh`'s by `match`) and `rows`: MasterFormFactorTable::rowsFor(mesh, ...)
/// with match.fresh() wanted. Nullopt where it cannot be made so, and the table must be assembled
/// anew: the exact columns changed (an emitter's patch split or merged, or their choice).
/// `storage`: a table no longer needed, whose arrays the result takes (FormFactorTable::
/// withRowSizes).
std::optional<FormFactorTable> updatedTable(const SymmetrizedTable& before, const PatchMesh& mesh,
                                            PatchMatch match,
                                            std::span<const uint32_t> exactColumns,
                                            const MasterFormFactorTable::Rows& rows, int levels,
                                            FormFactorTable storage = {});

}  // namespace rad
