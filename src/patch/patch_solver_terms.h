#pragma once
// Terms the patch solvers share: the norm of the emission, a patch's gather, the end of a solve.

#include <radiosity/error.h>

#include <cmath>
#include <span>

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

/// True when the last kRisingSweeps residuals each rose above the one before.
inline bool risingResiduals(std::span<const double> residuals) {
  if (residuals.size() <= size_t(kRisingSweeps)) return false;
  for (size_t k = residuals.size() - kRisingSweeps; k < residuals.size(); ++k)
    if (!(residuals[k] > residuals[k - 1])) return false;
  return true;
}

/// Records a relative residual; sets `converged` below the tolerance and `diverging` after
/// kRisingSweeps rises in a row. True when the solve should stop for either.
inline bool recordResidual(PatchSolution& out, double residual, double tolerance) {
  out.residuals.push_back(residual);
  out.converged = residual < tolerance;
  out.diverging = !out.converged && risingResiduals(out.residuals);
  return out.converged || out.diverging;
}

/// Ends a sweep: records its relative residual and reports progress (throws Cancelled when the
/// callback asks to stop). True when the solve stops: converged or diverging.
inline bool endSweep(PatchSolution& out, double change, double norm,
                     const PatchSolverControl& control, const ProgressCallback& progress) {
  ++out.iterations;
  const bool stop = recordResidual(out, change / norm, control.tolerance);
  if (progress && !progress(double(out.iterations) / control.maxIterations)) throw Cancelled();
  return stop;
}

/// A solve with no light put in has nothing to converge: it is solved as it starts.
inline void markNoLight(double norm, PatchSolution& out) {
  if (!(norm > 0.0)) out.converged = true;
}

/// Copies E into the solution.
inline void finishSolution(const PatchSystem& s, PatchSolution& out) {
  out.emitted = s.emitted;
}

}  // namespace rad
