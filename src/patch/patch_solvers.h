#pragma once
// Solvers of the radiosity equation on patches, B_i = E_i + rho_i (D_i + sum_j F_ij B_j), per
// RGB channel, where D_i is the direct irradiance from analytic lights (which have no area, so
// no form factors): their light enters as a first shot, rho_i D_i. Each stops once the relative
// residual, sum_i A_i |r_i| / sum_i A_i S_i (summed over the channels; S_i = E_i + rho_i D_i the
// light put in, r_i = E_i + rho_i H_i - B_i: the power not yet accounted for, relative to what is
// put in) is below the tolerance, or after maxIterations sweeps, or once the residual has risen
// kRisingSweeps sweeps in a row (diverging), and records it per sweep.

#include <radiosity/process_share.h>
#include <radiosity/progress.h>
#include <radiosity/types.h>

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "patch/form_factor_table.h"

namespace rad {

/// The patches' terms of the equation: E (emitted radiosity, pi Ke), rho, area and D (direct
/// irradiance from analytic lights; empty: none).
struct PatchSystem {
  std::vector<Color> emitted;
  std::vector<Color> rho;
  std::vector<float> area;
  std::vector<Color> direct;
  size_t size() const { return area.size(); }
  Color directAt(size_t i) const { return direct.empty() ? Color(0.0f) : direct[i]; }
  /// S_i = E_i + rho_i D_i: the radiosity the patch has before any bounce.
  Color source(size_t i) const { return emitted[i] + rho[i] * directAt(i); }
};

/// Sweeps in a row whose residual rose above the one before, after which a solve stops as
/// diverging. On a table bounded by FormFactorTable::boundReflection the residual's power never
/// grows, so a run of rises is a table that creates light (or a residual at float precision);
/// ten, so that a few rises of rounding never stop a solve.
constexpr int kRisingSweeps = 10;

struct PatchSolverControl {
  double tolerance = 1e-3;
  int maxIterations = 1000;  ///< sweeps; progressive refinement: shots / patches
  /// Jacobi split among processes: each sweeps its block of the patches and the sweep's
  /// radiosity is exchanged (null or one process: the whole sweep here).
  const ProcessShare* processes = nullptr;
};

struct PatchSolution {
  std::vector<Color> emitted;     ///< E
  std::vector<Color> irradiance;  ///< H = D + F B, incident power per area
  std::vector<Color> radiosity;   ///< B = E + rho H, excident power per area
  std::vector<double> residuals;  ///< relative residual after each sweep
  int iterations = 0;
  bool converged = false;  ///< the residual fell below the tolerance (or there was no light)
  bool diverging = false;  ///< stopped early: the residual rose kRisingSweeps sweeps in a row
  uint64_t shots = 0;      ///< progressive refinement: patches shot
  double seconds = 0.0;
};

/// Jacobi gathering: every patch gathers from the previous sweep's B (parallel).
PatchSolution solveJacobi(const FormFactorTable& table, const PatchSystem& system,
                          const PatchSolverControl& control, const ProgressCallback& progress = {});
/// Gauss-Seidel gathering: in place, each patch gathers the newest B (serial).
PatchSolution solveGaussSeidel(const FormFactorTable& table, const PatchSystem& system,
                               const PatchSolverControl& control,
                               const ProgressCallback& progress = {});

/// One row of F, as the progressive solver asks for it.
struct FormFactorRowView {
  std::span<const uint32_t> columns;
  std::span<const float> values;
};
/// Gives row i; called from one thread; the view must stay valid until the solver returns.
using FormFactorRowSource = std::function<FormFactorRowView(uint32_t patch)>;
/// The rows of `table` (which must outlive the source).
FormFactorRowSource rowsOf(const FormFactorTable& table);

/// Progressive refinement: shoots the patch with the most unshot power (Southwell iteration),
/// asking for each row when its patch first shoots; adds the ambient term at the end.
PatchSolution solveProgressive(const FormFactorRowSource& rows, const PatchSystem& system,
                               const PatchSolverControl& control,
                               const ProgressCallback& progress = {});

/// A progressive solve part way: B, H and the unshot radiosity U, where what has been shot is
/// exact, B = S + rho F (B - U) and H = D + F (B - U), and U is what is left to bounce.
struct ShootingState {
  std::vector<Color> radiosity, irradiance, unshot;
};
/// Shoots the patch with the most unshot power until the unshot power, sum_i A_i |U_i|, is below
/// control.tolerance times `norm` (or after control.maxIterations x patches shots, or once it
/// rose kRisingSweeps records in a row); records the shots and the relative unshot power per
/// patches-many shots in `record`, and whether it converged or diverged. Progressive refinement
/// warm-started from any state that keeps the equations above, which is what relighting shoots
/// a change of the light from.
void shootUnshot(const FormFactorRowSource& rows, const PatchSystem& system, ShootingState& state,
                 double norm, const PatchSolverControl& control, PatchSolution& record,
                 const ProgressCallback& progress = {});
/// The same bounced sweep by sweep: every patch shoots its unshot radiosity at once (a Jacobi
/// iteration of what is left; parallel, and no ordering to keep), until the unshot power is
/// below control.tolerance times `norm`, after control.maxIterations sweeps, or once it rose
/// kRisingSweeps sweeps in a row; records as shootUnshot does.
void shootUnshotInSweeps(const FormFactorTable& table, const PatchSystem& system,
                         ShootingState& state, double norm, const PatchSolverControl& control,
                         PatchSolution& record);
/// The solution a shooting state stands for: its B and H plus the ambient term of progressive
/// refinement for what is left unshot (the unshot power spread over the total area, times the
/// interreflection factor 1 / (1 - mean rho)), and E. Sets those arrays of `out`.
void solutionOf(const PatchSystem& system, const ShootingState& state, PatchSolution& out);

/// Relative residual of B for the system (for tests and reports).
double relativeResidual(const FormFactorTable& table, const PatchSystem& system,
                        std::span<const Color> radiosity);

}  // namespace rad
