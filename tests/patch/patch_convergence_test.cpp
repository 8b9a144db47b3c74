// Solves that converge or say so: the table's reflected share bounded below 1 (a row summing past
// 1 with rho near 1 made a real interior's Gauss-Seidel residual rise from sweep 193 on), a
// residual that keeps rising stopped as diverging, and a solve that ends above its tolerance
// warned of with its numbers.
#include <gtest/gtest.h>
#include <radiosity/patch_radiosity.h>

#include <algorithm>
#include <string>

#include "patch/patch_solver_terms.h"
#include "patch/patch_solvers.h"
#include "patch_test_scenes.h"

namespace rad {
namespace {

constexpr float kRho = kMaxReflectance;  // 0.999: what a glTF's reflectance of 1 becomes

// An integrating sphere cut into n patches of unequal areas: from anywhere inside a sphere the
// form factor to a patch is its share of the sphere's area, F_ij = A_j / A (Cohen and Wallace
// 1993, section 4.4, the sphere's closed form), so every row sums to 1. Every patch emits E = 1
// and reflects kRho: B = E / (1 - rho) = 1000 everywhere.
struct Sphere {
  FormFactorTable table;
  PatchSystem system;
};
Sphere integratingSphere(size_t n) {
  Sphere s;
  double total = 0.0;
  for (size_t i = 0; i < n; ++i) {
    s.system.area.push_back(1.0f + 0.25f * float(i % 5));
    total += s.system.area.back();
  }
  std::vector<std::vector<FormFactorEntry>> rows(n);
  for (size_t i = 0; i < n; ++i)
    for (uint32_t j = 0; j < n; ++j) rows[i].push_back({j, float(s.system.area[j] / total)});
  s.table = FormFactorTable::fromRows(std::move(rows));
  s.system.emitted.assign(n, Color(1.0f));
  s.system.rho.assign(n, Color(kRho));
  return s;
}

std::vector<float> reflectances(const PatchSystem& s) {
  std::vector<float> rho;
  for (const Color& c : s.rho) rho.push_back(maxComponent(c));
  return rho;
}

// The three solvers on one table and system.
std::vector<std::pair<std::string, PatchSolution>> solveAll(const FormFactorTable& table,
                                                            const PatchSystem& system,
                                                            const PatchSolverControl& control) {
  return {{"jacobi", solveJacobi(table, system, control)},
          {"gauss-seidel", solveGaussSeidel(table, system, control)},
          {"progressive", solveProgressive(rowsOf(table), system, control)}};
}

TEST(PatchConvergence, IntegratingSphereOfRho0999ReachesTheClosedForm) {
  Sphere sphere = integratingSphere(64);
  // Rows of 1 in floats, rho 0.999: shares of 0.999 to float rounding, scaled by a few ulps.
  sphere.table.boundReflection(reflectances(sphere.system), sphere.system.area, kMaxReflectance);
  // The residual falls by about rho a sweep: 1e-5 takes some 11,500 sweeps. What is left to
  // bounce, 1e-5 x rho / (1 - rho) of the light put in, is 1e-5 of B; B's float sums carry
  // their rounding through 1 / (1 - rho) = 1000 bounces: 1e-3 of B allowed.
  for (const auto& [name, solved] : solveAll(sphere.table, sphere.system, {1e-5, 40000})) {
    SCOPED_TRACE(name);
    EXPECT_TRUE(solved.converged);
    EXPECT_FALSE(solved.diverging);
    EXPECT_LT(solved.residuals.back(), 1e-5);
    for (size_t i = 0; i < sphere.system.size(); ++i)
      ASSERT_NEAR(solved.radiosity[i].g, 1000.0, 1.0) << "patch " << i;
  }
}

TEST(PatchConvergence, RowPastOneIsBoundAndTheSolveThenConverges) {
  // Patch 0's row and column made 20% larger (still reciprocal): row 0 sums to 1.2 and every
  // other row to 1 + 0.2 A_0 / A, so rho F's largest eigenvalue passes 1: the light grows by
  // about 0.2% a sweep, as a real interior's did.
  Sphere sphere = integratingSphere(64);
  FormFactorTable& table = sphere.table;
  for (size_t i = 0; i < table.rows(); ++i)
    for (size_t k = 0; k < table.columns(i).size(); ++k)
      if (i == 0 || table.columns(i)[k] == 0) table.rowValues(i)[k] *= 1.2f;
  const double rowSum0 = table.rowSum(0);  // 1.2, and 0.44 F_00 more for the diagonal
  ASSERT_GT(rowSum0, 1.2);

  const PatchSolverControl control{1e-5, 40000};
  for (const auto& [name, solved] : solveAll(table, sphere.system, control)) {
    SCOPED_TRACE(name + ", unbounded");
    EXPECT_TRUE(solved.diverging);
    EXPECT_FALSE(solved.converged);
    EXPECT_LT(solved.iterations, 100);  // stopped at the rises, not at the sweep limit
  }

  const std::vector<float> rho = reflectances(sphere.system);
  const FormFactorTable::ReflectionBound bound =
      table.boundReflection(rho, sphere.system.area, kMaxReflectance);
  EXPECT_EQ(bound.patches, table.rows());  // every patch had a share past 0.999
  EXPECT_NEAR(bound.worstShare, kRho * rowSum0, 1e-5);
  for (size_t i = 0; i < table.rows(); ++i) {
    // Both shares at most 0.999 (to float rounding), and reciprocity kept.
    double reflected = 0.0;
    for (size_t k = 0; k < table.columns(i).size(); ++k) {
      const uint32_t j = table.columns(i)[k];
      reflected += rho[j] * table.values(i)[k];
      const auto back = table.columns(j);
      const size_t at =
          size_t(std::lower_bound(back.begin(), back.end(), uint32_t(i)) - back.begin());
      EXPECT_NEAR(sphere.system.area[i] * table.values(i)[k],
                  sphere.system.area[j] * table.values(j)[at],
                  1e-6 * sphere.system.area[i] * table.values(i)[k]);
    }
    EXPECT_LE(kRho * table.rowSum(i), kMaxReflectance * (1.0 + 1e-6)) << "row " << i;
    EXPECT_LE(reflected, kMaxReflectance * (1.0 + 1e-6)) << "row " << i;
  }
  for (const auto& [name, solved] : solveAll(table, sphere.system, control)) {
    SCOPED_TRACE(name + ", bound");
    EXPECT_TRUE(solved.converged);
    EXPECT_FALSE(solved.diverging);
    // No row sends on more than it gathers: B stays below E / (1 - rho) (the maximum
    // principle), give or take the float sums' 1e-4.
    for (size_t i = 0; i < sphere.system.size(); ++i)
      EXPECT_LE(solved.radiosity[i].g, 1000.0f * (1.0f + 1e-4f)) << "patch " << i;
  }
  // A bound table is left alone.
  EXPECT_EQ(table.boundReflection(rho, sphere.system.area, kMaxReflectance * (1.0 + 1e-5)).patches,
            0u);
}

TEST(PatchConvergence, ResidualThatFallsThenRisesStopsAsDiverging) {
  // Two pairs of patches facing each other alone. Pair (0, 1), rho 0.9 and F 0.9 between them,
  // holds most of the light, and its change falls by 0.81 a sweep; pair (2, 3), rho 0.999 and
  // F 1.02 (a row past closure), holds 1e-4 of it, and its change grows by 1.019 a sweep. The
  // residual falls until the second pair's growth outweighs the first's decay, then rises: the
  // real interior's course (lowest at sweep 193, then rising to the limit).
  PatchSystem s;
  s.area.assign(4, 1.0f);
  s.emitted = {Color(1.0f), Color(1.0f), Color(1e-4f), Color(1e-4f)};
  s.rho = {Color(0.9f), Color(0.9f), Color(kRho), Color(kRho)};
  const FormFactorTable table =
      FormFactorTable::fromRows({{{1, 0.9f}}, {{0, 0.9f}}, {{3, 1.02f}}, {{2, 1.02f}}});
  for (const auto& [name, solved] : solveAll(table, s, {1e-9, 100000})) {
    SCOPED_TRACE(name);
    const std::vector<double>& r = solved.residuals;
    const size_t lowest = size_t(std::min_element(r.begin(), r.end()) - r.begin());
    EXPECT_GT(lowest, 5u);  // it fell first
    EXPECT_TRUE(solved.diverging);
    EXPECT_FALSE(solved.converged);
    // Stopped at the tenth rise in a row after its lowest (shooting's records, each as many
    // shots as patches, may wobble once or twice first), far before the sweep limit.
    EXPECT_GE(r.size(), lowest + 1 + size_t(kRisingSweeps));
    EXPECT_LE(r.size(), lowest + 1 + 2 * size_t(kRisingSweeps));
  }
}

// A closed box of reflectance 0.999 lit by its floor (E = 1), solved by PatchRadiosity with each
// solver: it must never diverge, and it either converges or says so. The hemisphere rays' rows
// scatter by a few percent about 1, and those past 1 are bound to 1 / 0.999, so light leaks
// from the table at some 2% a bounce and the solves converge in a few hundred sweeps; at 20
// sweeps every one ends above the tolerance, and warns. A box of 0.5 converges without a word.
TEST(PatchConvergence, ClosedBoxOfRho0999ConvergesOrWarnsAndNeverDiverges) {
  auto notConverged = [](const PatchRadiosityStats& stats) {
    return std::count_if(stats.warnings.begin(), stats.warnings.end(), [](const std::string& w) {
      return w.find("patch solve not converged") != std::string::npos;
    });
  };
  for (float rho : {kRho, 0.5f}) {
    const Scene scene = test::closedCube(rho);
    for (int sweeps : {20, 1000})
      for (PatchSolverKind solver :
           {PatchSolverKind::GaussSeidel, PatchSolverKind::Jacobi, PatchSolverKind::Progressive}) {
        SCOPED_TRACE(testing::Message() << "rho " << rho << ", " << sweeps << " sweeps, "
                                        << choiceName(kPatchSolverNames, solver));
        PatchRadiositySettings settings;
        settings.patchSize = 0.25f;
        settings.solver = solver;
        settings.maxIterations = sweeps;
        const PatchRadiosity solution(scene, settings);
        const PatchRadiosityStats& stats = solution.stats();
        // Bound: no row sends on more than 0.999 of what it gathers.
        EXPECT_LE(rho * stats.rowSumMax, kMaxReflectance * (1.0 + 1e-6));
        EXPECT_FALSE(stats.diverging);
        EXPECT_FALSE(risingResiduals(stats.residuals));
        EXPECT_EQ(notConverged(stats), stats.converged ? 0 : 1);
        // The patches scaled back are said: their light past closure is lost.
        const bool toldOfBound =
            std::any_of(stats.warnings.begin(), stats.warnings.end(), [](const std::string& w) {
              return w.find("scaled back to 0.999") != std::string::npos;
            });
        EXPECT_EQ(toldOfBound, stats.scaledForReflection > 0);
        if (rho == kRho) {
          EXPECT_GT(stats.scaledForReflection, 0u);
        }
        EXPECT_EQ(stats.converged, stats.residuals.back() < settings.tolerance);
        // No light made: the power leaving the surfaces stays below what the lamp's 1 W gives at
        // closure, 1 / (1 - rho) (to float rounding).
        Vec3d power(0.0);
        for (const ObjectRadiometry& o : solution.objectRadiometry())
          power += o.area * Vec3d(o.meanRadiosity);
        EXPECT_LT(power.g, 1.001 / (1.0 - rho));
        if (rho == 0.5f) {
          EXPECT_TRUE(stats.converged);
          continue;
        }
        if (sweeps > 20) continue;
        EXPECT_FALSE(stats.converged);
        ASSERT_FALSE(stats.warnings.empty());
        const std::string& w = stats.warnings.back();
        EXPECT_NE(w.find("(--max-iterations 20), above --tolerance 0.001"), std::string::npos) << w;
        EXPECT_NE(w.find("raise --max-iterations"), std::string::npos) << w;
        EXPECT_NE(w.find("up to 0.999"), std::string::npos) << w;
      }
  }
}

}  // namespace
}  // namespace rad
