// Jacobi iteration for the radiosity equation (Cohen and Wallace, "Radiosity and Realistic Image
// Synthesis" (1993), section 5.3.1): B^(k+1) = E + rho F B^(k). Converges because no patch's
// light comes back from a bounce stronger than 0.999 of it (FormFactorTable::boundReflection),
// so each sweep shrinks the residual's power.
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <chrono>

#include "core/process_collectives.h"
#include "patch/patch_solver_terms.h"
#include "patch/patch_solvers.h"

namespace rad {

double relativeResidual(const FormFactorTable& table, const PatchSystem& system,
                        std::span<const Color> radiosity) {
  const double norm = sourceNorm(system);
  double sum = 0.0;
  for (size_t i = 0; i < system.size(); ++i) {
    const Color h = system.directAt(i) + gather(table, i, radiosity);
    sum += double(system.area[i]) * absSum(system.emitted[i] + system.rho[i] * h - radiosity[i]);
  }
  return norm > 0.0 ? sum / norm : 0.0;
}

PatchSolution solveJacobi(const FormFactorTable& table, const PatchSystem& s,
                          const PatchSolverControl& control, const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  PatchSolution out;
  const double norm = sourceNorm(s);
  out.radiosity = sources(s);
  // H = D exactly while B is all zero: the answer of a solve with no light put in (everything
  // black, or every emitter off), which the sweeps below never start.
  out.irradiance = directIrradiance(s);
  std::vector<Color> next(s.size());
  const bool split = control.processes && control.processes->split();
  // Its own block of the patches (all of them in one process).
  const std::pair<size_t, size_t> block =
      split ? control.processes->block(s.size()) : std::pair<size_t, size_t>(0, s.size());
  while (norm > 0.0 && out.iterations < control.maxIterations) {
    double change = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(block.first, block.second, 1024), 0.0,
        [&](const tbb::blocked_range<size_t>& r, double acc) {
          for (size_t i = r.begin(); i < r.end(); ++i) {
            out.irradiance[i] = s.directAt(i) + gather(table, i, out.radiosity);
            next[i] = s.emitted[i] + s.rho[i] * out.irradiance[i];
            acc += double(s.area[i]) * absSum(next[i] - out.radiosity[i]);
          }
          return acc;
        },
        std::plus<double>());
    if (split) {  // every process's block of H and of the next B, and the change summed
      gatherBlocks(*control.processes, out.irradiance);
      gatherBlocks(*control.processes, next);
      change = sumOverProcesses(*control.processes, change);
    }
    out.radiosity.swap(next);
    if (endSweep(out, change, norm, control, progress)) break;
  }
  markNoLight(norm, out);
  finishSolution(s, out);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace rad
