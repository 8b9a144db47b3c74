// Gauss-Seidel iteration for the radiosity equation (Cohen and Wallace, "Radiosity and Realistic
// Image Synthesis" (1993), section 5.3.2): each patch gathers the newest radiosities, in place,
// which roughly halves the sweeps Jacobi needs on diagonally dominant systems.

#include <chrono>

#include "patch/patch_solver_terms.h"
#include "patch/patch_solvers.h"

namespace rad {

PatchSolution solveGaussSeidel(const FormFactorTable& table, const PatchSystem& s,
                               const PatchSolverControl& control,
                               const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  PatchSolution out;
  const double norm = sourceNorm(s);
  out.radiosity = sources(s);
  // H = D exactly while B is all zero: the answer of a solve with no light put in (everything
  // black, or every emitter off), which the sweeps below never start.
  out.irradiance = directIrradiance(s);
  while (norm > 0.0 && out.iterations < control.maxIterations) {
    double change = 0.0;
    for (size_t i = 0; i < s.size(); ++i) {
      out.irradiance[i] = s.directAt(i) + gather(table, i, out.radiosity);
      const Color b = s.emitted[i] + s.rho[i] * out.irradiance[i];
      change += double(s.area[i]) * absSum(b - out.radiosity[i]);
      out.radiosity[i] = b;
    }
    if (endSweep(out, change, norm, control, progress)) break;
  }
  markNoLight(norm, out);
  finishSolution(s, out);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace rad
