// Jacobi iteration for the radiosity equation (Cohen and Wallace, "Radiosity and Realistic Image
// Synthesis" (1993), section 5.3.1): B^(k+1) = E + rho F B^(k). Converges because rho F has
// spectral radius below 1 (rho < 1, rows of F sum to at most 1).
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <chrono>
#include <cstring>

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

namespace {

// A split sweep's end: every process's block of H and of the next B, gathered into every
// process (each element as its process computed it), and the change of B summed in rank order.
double exchangeSweep(const ProcessShare& share, std::vector<Color>& irradiance,
                     std::vector<Color>& next, double change) {
  const auto [first, last] = share.block(next.size());
  std::vector<char> mine(sizeof change + 2 * (last - first) * sizeof(Color));
  std::memcpy(mine.data(), &change, sizeof change);
  std::memcpy(mine.data() + sizeof change, irradiance.data() + first,
              (last - first) * sizeof(Color));
  std::memcpy(mine.data() + sizeof change + (last - first) * sizeof(Color), next.data() + first,
              (last - first) * sizeof(Color));
  const std::vector<char> all = share.gatherAll(mine);
  double total = 0.0;
  size_t at = 0;
  for (int rank = 0; rank < share.count; ++rank) {
    const auto [begin, end] = share.block(next.size(), rank);
    double c = 0.0;
    std::memcpy(&c, all.data() + at, sizeof c);
    total += c;
    at += sizeof c;
    std::memcpy(irradiance.data() + begin, all.data() + at, (end - begin) * sizeof(Color));
    at += (end - begin) * sizeof(Color);
    std::memcpy(next.data() + begin, all.data() + at, (end - begin) * sizeof(Color));
    at += (end - begin) * sizeof(Color);
  }
  return total;
}

}  // namespace

PatchSolution solveJacobi(const FormFactorTable& table, const PatchSystem& s,
                          const PatchSolverControl& control, const ProgressCallback& progress) {
  static_assert(sizeof(Color) == 3 * sizeof(float), "radiosity is exchanged as floats");
  const auto start = std::chrono::steady_clock::now();
  PatchSolution out;
  const double norm = sourceNorm(s);
  out.radiosity = sources(s);
  out.irradiance.assign(s.size(), Color(0.0f));
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
    if (split) change = exchangeSweep(*control.processes, out.irradiance, next, change);
    out.radiosity.swap(next);
    if (endSweep(out, change, norm, control, progress)) break;
  }
  finishSolution(s, out);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace rad
