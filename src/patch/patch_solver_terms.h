#pragma once
// Terms the patch solvers share: the norm of the emission, a patch's gather, the end of a solve.

#include <radiosity/error.h>

#include <cmath>

#include "patch/patch_solvers.h"

namespace rad {

/// sum_i A_i (E_r + E_g + E_b): the residual's denominator.
inline double emittedNorm(const PatchSystem& s) {
  double norm = 0.0;
  for (size_t i = 0; i < s.size(); ++i)
    norm += double(s.area[i]) * (double(s.emitted[i].r) + s.emitted[i].g + s.emitted[i].b);
  return norm;
}

inline double absSum(const Color& c) {
  return std::abs(double(c.r)) + std::abs(double(c.g)) + std::abs(double(c.b));
}

/// H_i = sum_j F_ij B_j.
inline Color gather(const FormFactorTable& table, size_t i, std::span<const Color> radiosity) {
  const auto cols = table.columns(i);
  const auto vals = table.values(i);
  Vec3d h(0.0);
  for (size_t k = 0; k < cols.size(); ++k) h += double(vals[k]) * Vec3d(radiosity[cols[k]]);
  return Color(h);
}

/// Ends a sweep: records its relative residual and reports progress (throws Cancelled when the
/// callback asks to stop). True when the tolerance is reached.
inline bool endSweep(PatchSolution& out, double change, double norm, const PatchSolverControl& control,
                     const ProgressCallback& progress) {
  ++out.iterations;
  out.residuals.push_back(change / norm);
  if (progress && !progress(double(out.iterations) / control.maxIterations)) throw Cancelled();
  return out.residuals.back() < control.tolerance;
}

/// Copies E into the solution.
inline void finishSolution(const PatchSystem& s, PatchSolution& out) { out.emitted = s.emitted; }

}  // namespace rad
