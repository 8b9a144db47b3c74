// Progressive refinement radiosity: M. Cohen, S. Chen, J. Wallace and D. Greenberg, "A
// progressive refinement approach to fast radiosity image generation", SIGGRAPH 1988. The patch
// with the most unshot power shoots it to every patch it sees (Southwell iteration; the unshot
// radiosity is exactly the residual of the gathering form). Shooting from i needs row i only,
// F_ji following from reciprocity F_ji = F_ij A_i / A_j, so rows are computed when first needed.
// The ambient term (their section 3.2) stands in for the power not yet shot.
#include <radiosity/error.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <chrono>
#include <queue>

#include "patch/patch_solver_terms.h"
#include "patch/patch_solvers.h"

namespace rad {

namespace {

struct Shooter {
  double power;
  uint32_t patch;
  bool operator<(const Shooter& o) const { return power < o.power; }
};

}  // namespace

FormFactorRowSource rowsOf(const FormFactorTable& table) {
  return [&table](uint32_t i) { return FormFactorRowView{table.columns(i), table.values(i)}; };
}

namespace {

// The ambient irradiance: unshot power spread over the total area, times the interreflection
// factor 1 / (1 - mean rho).
Color ambientTerm(const PatchSystem& s, std::span<const Color> unshot) {
  Vec3d shot(0.0), rho(0.0);
  double area = 0.0;
  for (size_t i = 0; i < s.size(); ++i) {
    shot += double(s.area[i]) * Vec3d(unshot[i]);
    rho += double(s.area[i]) * Vec3d(s.rho[i]);
    area += s.area[i];
  }
  if (area <= 0.0) return Color(0.0f);
  return Color(shot / area / (Vec3d(1.0) - rho / area));
}

}  // namespace

void solutionOf(const PatchSystem& s, const ShootingState& state, PatchSolution& out) {
  const Color ambient = ambientTerm(s, state.unshot);
  out.radiosity = state.radiosity;
  out.irradiance = state.irradiance;
  for (size_t i = 0; i < s.size(); ++i) {
    out.irradiance[i] += ambient;
    out.radiosity[i] += s.rho[i] * ambient;
  }
  finishSolution(s, out);
}

void shootUnshot(const FormFactorRowSource& rows, const PatchSystem& s, ShootingState& state,
                 double norm, const PatchSolverControl& control, PatchSolution& record,
                 const ProgressCallback& progress) {
  const size_t n = s.size();
  std::vector<Color>& unshot = state.unshot;
  std::vector<double> power(n);
  std::priority_queue<Shooter> queue;
  double total = 0.0;
  auto rebuild = [&] {  // also removes the drift of the running total
    queue = {};
    total = 0.0;
    for (uint32_t i = 0; i < n; ++i) {
      power[i] = double(s.area[i]) * absSum(unshot[i]);
      total += power[i];
      if (power[i] > 0.0) queue.push({power[i], i});
    }
  };
  rebuild();
  const uint64_t maxShots = uint64_t(std::max(control.maxIterations, 1)) * std::max<uint64_t>(n, 1);
  uint64_t shots = 0;
  record.diverging = false;
  while (norm > 0.0 && shots < maxShots && total / norm >= control.tolerance && !queue.empty() &&
         !record.diverging) {
    const Shooter top = queue.top();
    queue.pop();
    if (top.power != power[top.patch]) continue;  // stale: the patch received since
    const uint32_t i = top.patch;
    const Color shot = unshot[i];
    unshot[i] = Color(0.0f);
    total -= power[i];
    power[i] = 0.0;
    const FormFactorRowView row = rows(i);
    for (size_t k = 0; k < row.columns.size(); ++k) {
      const uint32_t j = row.columns[k];
      const Color h = shot * (row.values[k] * s.area[i] / s.area[j]);
      state.irradiance[j] += h;
      const Color b = s.rho[j] * h;
      state.radiosity[j] += b;
      unshot[j] += b;
      const double p = double(s.area[j]) * absSum(unshot[j]);
      total += p - power[j];
      power[j] = p;
      if (p > 0.0) queue.push({p, j});
    }
    if (++shots % std::max<uint64_t>(n, 1) == 0) {
      rebuild();
      ++record.iterations;
      recordResidual(record, total / norm, control.tolerance);
      if (progress && !progress(double(shots) / double(maxShots))) throw Cancelled();
    }
    if (queue.size() > 8 * n + 1024) rebuild();
  }
  if (record.residuals.empty() || shots % std::max<uint64_t>(n, 1) != 0) {
    ++record.iterations;
    recordResidual(record, norm > 0.0 ? total / norm : 0.0, control.tolerance);
  }
  markNoLight(norm, record);
  record.shots += shots;
}

void shootUnshotInSweeps(const FormFactorTable& table, const PatchSystem& s, ShootingState& state,
                         double norm, const PatchSolverControl& control, PatchSolution& record) {
  const size_t n = s.size();
  std::vector<Color> received(n);
  auto unshotPower = [&] {
    return tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, n), 0.0,
        [&](const tbb::blocked_range<size_t>& r, double sum) {
          for (size_t i = r.begin(); i != r.end(); ++i)
            sum += double(s.area[i]) * absSum(state.unshot[i]);
          return sum;
        },
        std::plus<>());
  };
  double power = unshotPower();
  record.diverging = false;
  for (int sweep = 0; norm > 0.0 && sweep < control.maxIterations &&
                      power >= control.tolerance * norm && !record.diverging;
       ++sweep) {
    tbb::parallel_for(size_t(0), n,
                      [&](size_t i) { received[i] = gather(table, i, state.unshot); });
    tbb::parallel_for(size_t(0), n, [&](size_t i) {
      const Color b = s.rho[i] * received[i];
      state.irradiance[i] += received[i];
      state.radiosity[i] += b;
      state.unshot[i] = b;
    });
    record.shots += n;
    power = unshotPower();
    ++record.iterations;
    recordResidual(record, power / norm, control.tolerance);
  }
  if (record.residuals.empty())
    recordResidual(record, norm > 0.0 ? power / norm : 0.0, control.tolerance);
  markNoLight(norm, record);
}

PatchSolution solveProgressive(const FormFactorRowSource& rows, const PatchSystem& s,
                               const PatchSolverControl& control,
                               const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  PatchSolution out;
  ShootingState state{sources(s), directIrradiance(s), sources(s)};
  shootUnshot(rows, s, state, sourceNorm(s), control, out, progress);
  solutionOf(s, state, out);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace rad
