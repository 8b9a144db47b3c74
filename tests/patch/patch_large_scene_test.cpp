// The patch method on scenes of many faces and of patches of very different sizes: its budget,
// the closure of its form-factor rows and the energy balance, which real scenes broke.
#include <gtest/gtest.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/run_stats.h>
#include <radiosity/scene_builder.h>
#include <radiosity/scene_loader.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "patch/form_factor_table.h"
#include "patch/patch_mesh.h"
#include "render/test_scenes.h"

namespace fs = std::filesystem;

namespace rad {
namespace {

TEST(PatchBudget, ManyFacesStillSplitTheLargeOnes) {
  // room:400 has 9,875 faces, more than the 4,000 patches asked for: the target counts the
  // patches beyond one per face, so its 40 m floor is still split. Before, the search for "at
  // least 4,000 patches" ended at its largest size (113 m): one patch per face.
  const Scene scene = loadScene("room:400");
  const PatchMesh mesh(scene, {0.0f, 4000});
  EXPECT_GE(mesh.size(), scene.faces.size() + 4000);
  EXPECT_LE(mesh.size(), 4 * (scene.faces.size() + 4000));
  EXPECT_LT(mesh.patchSize(), 40.0f / 8.0f);
}

// A closed hall of 80 x 80 x 10 m with a 0.3 m square lamp 1 m above the floor at (x, z),
// facing down.
Scene hallWithASmallLamp(float x = 40.0f, float z = 40.0f) {
  SceneBuilder b("hall");
  const uint32_t grey = b.addMaterial({"grey", Color(0.5f)});
  const uint32_t lamp = b.addMaterial({"lamp", Color(0.0f), Color(100.0f)});
  const uint32_t hall = b.addObject("hall");
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const Vec3 size(80.0f, 10.0f, 80.0f);
      Vec3 centre = 0.5f * size;
      centre[axis] = side == 0 ? 0.0f : size[axis];
      Vec3 inward(0.0f);
      inward[axis] = side == 0 ? 1.0f : -1.0f;
      std::array<Vec3, 4> quad = test::axisSquare(Vec3(0.0f), axis, 1.0f);
      for (Vec3& p : quad) p = centre + p * size;
      test::addQuadFacing(b, quad, inward, grey, hall);
    }
  test::addQuadFacing(b, test::axisSquare(Vec3(x, 1.0f, z), 1, 0.3f), Vec3(0, -1, 0), lamp,
                      b.addObject("lamp"));
  return b.build();
}

TEST(PatchClosure, SmallEmitterBesideALargePatchKeepsTheEnergyBalance) {
  // One patch per face (patch size 1000): the floor's form factor toward the lamp was integrated
  // at 16 points of the floor, 20 m apart. Over the middle of the floor they miss the kernel's
  // peak under the lamp: its reciprocal, the lamp's row, came out 0.014 (the closed hall
  // absorbed 1.3% of what the lamp emits). Over (30, 30), a point lies right under the lamp:
  // the row came out 124 (a real atrium's lamps: rows up to 325, 1.5 to 2 times the power).
  // Integrated over the smaller patch of each pair, toward the other's polygon, the closed hall
  // absorbs what it emits, and no row sums past 1 plus noise.
  for (const float at : {40.0f, 30.0f}) {
    const Scene scene = hallWithASmallLamp(at, at);
    PatchRadiositySettings settings;
    settings.patchSize = 1000.0f;
    settings.cacheDir = "";
    const PatchRadiosity solution(scene, settings);
    EXPECT_EQ(solution.stats().exactColumns, 1u);
    EXPECT_LE(solution.stats().rowSumEstimatedMax, 1.25) << at;
    const Color emitted = scene.emittedPower();
    const Color absorbed = absorbedPower(scene, solution.objectRadiometry());
    EXPECT_NEAR(absorbed.g, emitted.g, 0.02 * emitted.g) << at;
  }
}

TEST(PatchClosure, RowsPastOnePlusNoiseAreScaledBackKeepingReciprocity) {
  // Three patches of areas 1, 2 and 4; the first row sums to 2 (a forged estimate), the others
  // to less than 1. Closed with a noise of 0.25, every row sums to at most 1.25, the first to
  // 1, and A_i F_ij = A_j F_ji still holds.
  const std::vector<float> area{1.0f, 2.0f, 4.0f};
  std::vector<std::vector<FormFactorEntry>> rows{
      {{1, 1.2f}, {2, 0.8f}}, {{0, 0.6f}, {2, 0.3f}}, {{0, 0.2f}, {1, 0.15f}}};
  FormFactorTable table = FormFactorTable::fromRows(std::move(rows));
  const FormFactorTable::ClosureRepair repair = table.closeRows(0.25);
  EXPECT_EQ(repair.rows, 1u);
  EXPECT_NEAR(repair.worstSum, 2.0, 1e-6);
  EXPECT_NEAR(table.rowSum(0), 1.0, 1e-6);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_LE(table.rowSum(i), 1.25);
    for (size_t k = 0; k < table.columns(i).size(); ++k) {
      const uint32_t j = table.columns(i)[k];
      const std::span<const uint32_t> back = table.columns(j);
      const size_t at = size_t(std::find(back.begin(), back.end(), uint32_t(i)) - back.begin());
      ASSERT_LT(at, back.size());
      EXPECT_NEAR(area[i] * table.values(i)[k], area[j] * table.values(j)[at], 1e-6);
    }
  }
}

TEST(PatchClosure, CacheReadsBackWhatItWrote) {
  // The whole-table cache (pairwise estimator) and the master table (hemisphere) of the hall at
  // one patch per face: the second solve loads the first's table and gets its answer.
  for (const PatchFormFactorEstimator estimator :
       {PatchFormFactorEstimator::Pairwise, PatchFormFactorEstimator::Hemisphere}) {
    const Scene scene = hallWithASmallLamp();
    const fs::path dir = fs::path(::testing::TempDir()) /
                         ("radiosity_closure_cache_" + std::to_string(int(estimator)));
    fs::remove_all(dir);
    PatchRadiositySettings settings;
    settings.patchSize = 1000.0f;
    settings.estimator = estimator;
    settings.cacheDir = dir.string();
    const PatchRadiosity first(scene, settings), again(scene, settings);
    EXPECT_FALSE(first.stats().cacheLoaded);
    EXPECT_TRUE(again.stats().cacheLoaded)
        << (again.stats().warnings.empty() ? "" : again.stats().warnings[0]);
    EXPECT_EQ(again.objectRadiometry()[1].meanIrradiance,
              first.objectRadiometry()[1].meanIrradiance);
    fs::remove_all(dir);
  }
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

// A textured interior: each patch takes its texture's mean over its own footprint, the path
// tracer the texel at each point; per object, the light leaving (B = rho H, where the texture
// shows) agrees within 5% (the bound). Measured at 4,000 patches: -0.4..+0.7% per
// object.
TEST(PatchRealInterior, TexturedAtriumMatchesThePathTracerPerObject) {
  const Scene scene = loadScene("atrium-textured:1");
  const std::map<std::string, ObjectRadiometry> traced =
      test::tracedObjectMeans(scene, 20000, 4, 11);
  PatchRadiositySettings settings;
  settings.targetPatches = 4000;
  const PatchRadiosity solution = PatchModel(scene, settings).solve(scene.lights);
  for (const ObjectRadiometry& o : solution.objectRadiometry()) {
    const float expected = luminance(traced.at(o.name).meanRadiosity);
    const float got = luminance(o.meanRadiosity);
    std::printf("%-15s B %.4f traced %.4f (%+.1f%%)\n", o.name.c_str(), got, expected,
                100.0 * (got / expected - 1.0));
    EXPECT_NEAR(got, expected, 0.05f * expected) << o.name;
  }
}

}  // namespace
}  // namespace rad
