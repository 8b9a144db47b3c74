#pragma once
// The precomputed transfer of a patch mesh: the response of every patch to unit radiosity put
// into every patch, T = (I - rho F)^-1 per colour channel (B = T S for sources S), as dense
// columns. Relighting through it is one column per changed patch (B += T dS) instead of shooting
// the change until it has bounced out. Memory and build time grow as N^2 and N^3, so it is for
// small meshes that do not change (no adaptive subdivision): the relighter's other path, delta
// shooting, is linear in the table and follows a changing quadtree.
// After the transfer-matrix relighting of precomputed radiance transfer (P.-P. Sloan, J. Kautz
// and J. Snyder, SIGGRAPH 2002), here for diffuse patches and their direct light.

#include <radiosity/progress.h>
#include <radiosity/types.h>

#include <span>
#include <vector>

#include "patch/form_factor_table.h"
#include "patch/patch_solvers.h"

namespace rad {

class PrecomputedTransfer {
 public:
  /// The transfer of the system (its rho) through `table`, by an LU factorization per channel
  /// (Eigen). Throws rad::Cancelled if `progress` returns false.
  PrecomputedTransfer(const FormFactorTable& table, const PatchSystem& system,
                      const ProgressCallback& progress = {});

  size_t patches() const { return n_; }
  /// Adds (T - I) u to `radiosity` and F T u to `irradiance`: what the radiosity `u` put into
  /// the patches (nonzero at few of them) adds once it has bounced out.
  void propagate(std::span<const Color> u, const FormFactorTable& table,
                 std::vector<Color>& radiosity, std::vector<Color>& irradiance) const;
  size_t memoryBytes() const { return columns_.size() * sizeof(float); }

 private:
  size_t n_ = 0;
  /// Channel c's column k at (c * n + k) * n: T_c(., k).
  std::vector<float> columns_;
};

}  // namespace rad
