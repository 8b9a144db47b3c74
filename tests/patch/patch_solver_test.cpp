// The patch solvers against a dense direct solve, and the closure and energy identities of
// docs/references.md section 3.
#include <gtest/gtest.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/ray_caster.h>

#include <Eigen/Dense>

#include "patch/form_factor_estimators.h"
#include "patch/patch_solvers.h"
#include "patch_test_scenes.h"

namespace rad {
namespace {

// The unit cube seen from inside, each face its own colour, face 0 emitting.
Scene colouredCube() {
  SceneBuilder b("cube");
  const Color rho[6] = {{0.3f, 0.3f, 0.3f}, {0.8f, 0.2f, 0.1f}, {0.1f, 0.7f, 0.2f},
                        {0.6f, 0.6f, 0.6f}, {0.2f, 0.3f, 0.9f}, {0.5f, 0.5f, 0.1f}};
  const char* const kNames[6] = {"m0", "m1", "m2", "m3", "m4", "m5"};
  std::vector<uint32_t> m;
  for (int f = 0; f < 6; ++f)
    m.push_back(
        b.addMaterial({kNames[f], rho[f], f == 0 ? Color(1.0f, 0.8f, 0.6f) : Color(0.0f), false}));
  test::addInwardCube(b, [&](int face) { return m[face]; });
  return b.build();
}

PatchSystem systemOf(const Scene& scene, const PatchMesh& mesh) {
  PatchSystem s;
  for (const Patch& p : mesh.patches()) {
    s.emitted.push_back(glm::pi<float>() * scene.materials[p.material].emission);
    s.rho.push_back(scene.materials[p.material].rho);
    s.area.push_back(p.area);
  }
  return s;
}

// B of (I - diag(rho) F) B = E + diag(rho) D by LU, per channel (Eigen, independent of our
// solvers).
std::vector<Vec3d> denseSolve(const FormFactorTable& table, const PatchSystem& s) {
  const Eigen::Index n = Eigen::Index(s.size());
  std::vector<Vec3d> b(s.size());
  for (int c = 0; c < 3; ++c) {
    Eigen::MatrixXd m = Eigen::MatrixXd::Identity(n, n);
    Eigen::VectorXd e(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      e[i] = s.emitted[size_t(i)][c] + s.rho[size_t(i)][c] * s.directAt(size_t(i))[c];
      const auto cols = table.columns(size_t(i));
      for (size_t k = 0; k < cols.size(); ++k)
        m(i, cols[k]) -= s.rho[size_t(i)][c] * table.values(size_t(i))[k];
    }
    const Eigen::VectorXd x = m.partialPivLu().solve(e);
    for (Eigen::Index i = 0; i < n; ++i) b[size_t(i)][c] = x[i];
  }
  return b;
}

// Every solver against the dense solve: B to 1e-5 of the largest, B = E + rho H throughout.
void expectSolversAgreeWithDenseSolve(const FormFactorTable& table, const PatchSystem& system) {
  const std::vector<Vec3d> dense = denseSolve(table, system);
  double scale = 0.0;
  for (const Vec3d& b : dense) scale = std::max(scale, std::max(b.x, std::max(b.y, b.z)));
  ASSERT_GT(scale, 0.0);
  const PatchSolverControl control{1e-9, 100000};
  auto rowOf = [&](uint32_t i) { return FormFactorRowView{table.columns(i), table.values(i)}; };
  const PatchSolution solutions[3] = {solveJacobi(table, system, control),
                                      solveGaussSeidel(table, system, control),
                                      solveProgressive(rowOf, system, control)};
  for (const PatchSolution& s : solutions) {
    double worst = 0.0;
    for (size_t i = 0; i < dense.size(); ++i)
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, std::abs(double(s.radiosity[i][c]) - dense[i][c]));
    EXPECT_LT(worst / scale, 1e-5) << "solver " << (&s - solutions) << ", " << s.iterations
                                   << " sweeps, " << s.shots << " shots";
    EXPECT_LT(s.residuals.back(), 1e-9);
    EXPECT_LT(relativeResidual(table, system, s.radiosity), 1e-5);  // B is stored in float
    for (size_t i = 0; i < dense.size(); ++i)  // B = E + rho H (progressive: ambient term included)
      EXPECT_NEAR(s.radiosity[i].g, system.emitted[i].g + system.rho[i].g * s.irradiance[i].g,
                  1e-5 * scale);  // B and H are stored in float
  }
  // Gauss-Seidel uses the newest values: fewer sweeps than Jacobi.
  EXPECT_LT(solutions[1].iterations, solutions[0].iterations);
}

FormFactorTable cubeTable(const Scene& scene, const PatchMesh& mesh, const PatchSystem& system) {
  const RayCaster caster(scene);
  FormFactorTable table = FormFactorTable::fromRows(estimateFormFactors(mesh, caster, {}, {}));
  table.symmetrize(system.area);
  return table;
}

TEST(PatchSolvers, AgreeWithDenseSolveTo1e5) {
  const Scene scene = colouredCube();
  const PatchMesh mesh(scene, {0.25f, 0});
  const PatchSystem system = systemOf(scene, mesh);
  expectSolversAgreeWithDenseSolve(cubeTable(scene, mesh, system), system);
}

// Light from analytic lights enters as direct irradiance D (no emitting patch at all): the
// solvers start from rho D and bounce it.
TEST(PatchSolvers, AgreeWithDenseSolveWithDirectLightOnly) {
  const Scene scene = colouredCube();
  const PatchMesh mesh(scene, {0.25f, 0});
  PatchSystem system = systemOf(scene, mesh);
  for (size_t i = 0; i < system.size(); ++i) {
    system.emitted[i] = Color(0.0f);
    // An uneven pattern, as a spot gives: bright on a few patches, nothing on most.
    system.direct.push_back(i % 7 == 0 ? Color(3.0f, 2.0f, 1.0f) * float(1 + i % 3) : Color(0.0f));
  }
  expectSolversAgreeWithDenseSolve(cubeTable(scene, mesh, system), system);
}

// docs/references.md 3.4: every row of a closed box sums to 1 (the hemisphere rows before
// reciprocity averaging, and the exact estimator's rows), within 1%.
TEST(FormFactorClosure, ClosedBoxRowsSumToOne) {
  const Scene cube = test::uniformCube(Color(0.5f), Color(0.0f));
  const PatchMesh mesh(cube, {0.25f, 0});
  const RayCaster caster(cube);
  for (auto estimator : {FormFactorEstimator::Hemisphere, FormFactorEstimator::Exact}) {
    const FormFactorSettings settings{estimator, estimator == FormFactorEstimator::Exact ? 64 : 256,
                                      1};
    const FormFactorRows rows = estimateFormFactors(mesh, caster, settings, {});
    FormFactorTable table = FormFactorTable::fromRows(rows);
    for (size_t i = 0; i < table.rows(); ++i)
      EXPECT_NEAR(table.rowSum(i), 1.0, 0.01) << "row " << i;
    // After reciprocity averaging each row moves by noise, their mean stays at 1.
    std::vector<float> area(mesh.size(), 1.0f / 16.0f);
    table.symmetrize(area);
    double mean = 0.0;
    for (size_t i = 0; i < table.rows(); ++i) mean += table.rowSum(i) / double(table.rows());
    EXPECT_NEAR(mean, 1.0, 0.005);
  }
}

// docs/references.md 3.1 / 3.3: a closed box of uniform rho with one emitting face (E = 1) holds
// sum A B = sum A E / (1 - rho): 2 for rho = 0.5 and 5 for rho = 0.8, within 1%.
TEST(PatchRadiosityEnergy, ClosedRoomBalancesEmission) {
  for (float rho : {0.5f, 0.8f}) {
    const Scene scene = test::closedCube(rho);
    PatchRadiositySettings settings;
    settings.patchSize = 0.125f;
    settings.tolerance = 1e-6;
    const PatchRadiosity solution(scene, settings);
    Vec3d power(0.0);
    for (const ObjectRadiometry& o : solution.objectRadiometry())
      power += o.area * Vec3d(o.meanRadiosity);
    EXPECT_NEAR(power.g, 1.0 / (1.0 - rho), 0.01 / (1.0 - rho)) << "rho " << rho;
  }
}

}  // namespace
}  // namespace rad
