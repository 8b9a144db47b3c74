#pragma once
// Terms the patch solvers share: the norm of the emission, a patch's gather, the end of a solve.

#include <radiosity/error.h>

#include <cmath>

#include "patch/patch_solvers.h"

namespace rad {

/// sum_i A_i (S_r + S_g + S_b), S the light put in: the residual's denominator.
inline double sourceNorm(const PatchSystem& s) {
  double norm = 0.0;
  for (size_t i = 0; i < s.size(); ++i) {
    const Color source = s.source(i);
    norm += double(s.area[i]) * (double(source.r) + source.g + source.b);
  }
  return norm;
}

/// The radiosities before any bounce, S.
inline std::vector<Color> sources(const PatchSystem& s) {
  std::vector<Color> out(s.size());
  for (size_t i = 0; i < s.size(); ++i) out[i] = s.source(i);
  return out;
}

/// The irradiances before any bounce, D.
inline std::vector<Color> directIrradiance(const PatchSystem& s) {
  return s.direct.empty() ? std::vector<Color>(s.size(), Color(0.0f)) : s.direct;
}

inline double absSum(const Color& c) {
  return std::abs(double(c.r)) + std::abs(double(c.g)) + std::abs(double(c.b));
}

/// sum_j F_ij B_j, added in floats: a row's few hundred terms lose nothing visible there, and the
/// relighter's sweeps, which stream the whole table, took 10% longer summing in doubles.
inline Color gather(const FormFactorTable& table, size_t i, std::span<const Color> radiosity) {
  const auto cols = table.columns(i);
  const auto vals = table.values(i);
  Color h(0.0f);
  for (size_t k = 0; k < cols.size(); ++k) h += vals[k] * radiosity[cols[k]];
  return h;
}

/// Ends a sweep: records its relative residual and reports progress (throws Cancelled when the
/// callback asks to stop). True when the tolerance is reached.
inline bool endSweep(PatchSolution& out, double change, double norm,
                     const PatchSolverControl& control, const ProgressCallback& progress) {
  ++out.iterations;
  out.residuals.push_back(change / norm);
  if (progress && !progress(double(out.iterations) / control.maxIterations)) throw Cancelled();
  return out.residuals.back() < control.tolerance;
}

/// Copies E into the solution.
inline void finishSolution(const PatchSystem& s, PatchSolution& out) {
  out.emitted = s.emitted;
}

}  // namespace rad
