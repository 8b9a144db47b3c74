// The patch method end to end: the Cornell box against the path tracer, the disk cache, and
// radiance queries.
#include <gtest/gtest.h>
#include <radiosity/error.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/path_tracer.h>
#include <radiosity/run_stats.h>
#include <radiosity/scene_loader.h>
#include <sys/stat.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include "core/binary_io.h"
#include "patch/form_factor_estimators.h"
#include "patch/form_factor_table.h"
#include "patch_test_scenes.h"
#include "render/test_scenes.h"

namespace fs = std::filesystem;

namespace rad {
namespace {

// Each wall, the floor, the ceiling and both blocks: the area-weighted mean radiosity within 3%
// of the path tracer's. The reference's noise is dominated by where its points fall (shadows
// make the irradiance discontinuous): 400 points per object left the floor 5-7% off between
// seeds, so it takes 20000 points x 16 paths (measured: floor 0.5% between seeds, the others
// less).
TEST(PatchCornell, SurfaceMeansMatchThePathTracer) {
  const Scene scene = loadScene("cornell");
  const std::map<std::string, ObjectRadiometry> expected =
      test::tracedObjectMeans(scene, 20000, 16, 5);

  PatchRadiositySettings settings;  // the defaults: ~4000 patches, 256 rays each, Gauss-Seidel
  const PatchRadiosity solution(scene, settings);
  EXPECT_GE(solution.stats().patches, 4000u);
  int compared = 0;
  for (const ObjectRadiometry& o : solution.objectRadiometry()) {
    if (o.name == "light") continue;  // its radiosity is its emission, an input
    const ObjectRadiometry& ref = expected.at(o.name);
    EXPECT_NEAR(o.area, ref.area, 1e-3 * ref.area) << o.name;
    for (int c = 0; c < 3; ++c) {
      if (ref.meanRadiosity[c] < 0.02f) continue;  // a channel the paint absorbs almost fully
      EXPECT_NEAR(o.meanRadiosity[c], ref.meanRadiosity[c], 0.03 * ref.meanRadiosity[c])
          << o.name << " channel " << c;
      ++compared;
    }
  }
  EXPECT_GE(compared, 15);
}

// Progressive refinement without a cache casts each shooter's row when it shoots (no table): the
// emitters' exact columns must reach it too, as the light's row by reciprocity, or the lit
// surfaces would differ from the table's solution by the hemisphere rays' noise on the light.
// Both solve the same rows up to symmetrization: measured within 0.12% per surface and channel.
TEST(PatchCornell, LazyProgressiveAgreesWithTheTable) {
  const Scene scene = loadScene("cornell");
  PatchRadiositySettings settings;
  settings.cacheDir.clear();
  settings.tolerance = 1e-6;
  settings.solver = PatchSolverKind::GaussSeidel;
  const PatchRadiosity table(scene, settings);
  settings.solver = PatchSolverKind::Progressive;
  settings.maxIterations = 100000;
  const PatchRadiosity lazy(scene, settings);
  EXPECT_GT(table.stats().exactColumns, 0u);
  EXPECT_EQ(lazy.stats().exactColumns, table.stats().exactColumns);
  const std::vector<ObjectRadiometry> a = table.objectRadiometry(), b = lazy.objectRadiometry();
  ASSERT_EQ(a.size(), b.size());
  for (size_t o = 0; o < a.size(); ++o)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(b[o].meanRadiosity[c], a[o].meanRadiosity[c], 5e-3 * a[o].meanRadiosity[c] + 1e-6)
          << a[o].name << " channel " << c;
}

Scene smallRoom() {
  SceneBuilder b("cube");
  const uint32_t wall = b.addMaterial({"wall", Color(0.6f), Color(0.0f), false});
  const uint32_t lamp = b.addMaterial({"lamp", Color(0.3f), Color(1.0f), false});
  test::addInwardCube(b, [&](int face) { return face == 3 ? lamp : wall; });
  return b.build();
}

// A large emitter in fine patches is left to the hemisphere rays (its exact columns would cost
// too much), and the user is told: faces split in 32 x 32 patches make the lamp face 1024 of 6144
// patches, 6.3M pairs, above the 2M the exact columns take; at 16 x 16, 256 x 1536 = 0.39M pairs,
// they are exact.
TEST(PatchRadiosity, LargeEmittersFallBackToRaysWithAWarning) {
  const Scene scene = smallRoom();
  PatchRadiositySettings settings;
  settings.cacheDir.clear();
  settings.patchSize = 1.0f / 32.0f;
  const PatchRadiosity fine(scene, settings);
  EXPECT_EQ(fine.stats().patches, 6u * 32u * 32u);
  EXPECT_EQ(fine.stats().exactColumns, 0u);
  ASSERT_EQ(fine.stats().warnings.size(), 1u);
  EXPECT_NE(fine.stats().warnings[0].find("1024 emitter patches"), std::string::npos)
      << fine.stats().warnings[0];
  settings.patchSize = 1.0f / 16.0f;
  const PatchRadiosity coarse(scene, settings);
  EXPECT_EQ(coarse.stats().exactColumns, 256u);
  EXPECT_TRUE(coarse.stats().warnings.empty());
}

// The hemisphere estimator caches its master table by node; the others whole tables.
std::vector<ObjectRadiometry> solveWith(
    const Scene& scene, const fs::path& cache, PatchRadiosityStats& stats,
    PatchFormFactorEstimator estimator = PatchFormFactorEstimator::Hemisphere) {
  PatchRadiositySettings settings;
  settings.patchSize = 0.125f;
  settings.cacheDir = cache.string();
  settings.estimator = estimator;
  if (estimator == PatchFormFactorEstimator::Pairwise) settings.formFactorRays = 4;
  const PatchRadiosity solution(scene, settings);
  stats = solution.stats();
  return solution.objectRadiometry();
}

void expectSame(const std::vector<ObjectRadiometry>& a, const std::vector<ObjectRadiometry>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t o = 0; o < a.size(); ++o)
    EXPECT_EQ(a[o].meanRadiosity, b[o].meanRadiosity) << a[o].name;
}

void expectSecondRunLoadsAndBadFilesRecomputed(PatchFormFactorEstimator estimator) {
  // One folder per test: ctest runs the two estimators' tests in parallel.
  const fs::path dir = fs::path(::testing::TempDir()) /
                       ("radiosity_patch_cache_" +
                        std::string(testing::UnitTest::GetInstance()->current_test_info()->name()));
  fs::remove_all(dir);
  const Scene scene = smallRoom();
  PatchRadiosityStats first, again;
  const auto reference = solveWith(scene, dir, first, estimator);
  EXPECT_FALSE(first.cacheLoaded);
  EXPECT_TRUE(first.warnings.empty());
  ASSERT_TRUE(fs::exists(first.cacheFile));
  expectSame(solveWith(scene, dir, again, estimator), reference);
  EXPECT_TRUE(again.cacheLoaded);
  EXPECT_EQ(again.rays, 0u);  // nothing recomputed

  // Each damage: one warning, the table recomputed (and rewritten), the same answer.
  const std::string file = first.cacheFile;
  auto damageAndCheck = [&](const std::string& what,
                            const std::function<void(std::string&)>& damage,
                            const std::string& expectedReason) {
    SCOPED_TRACE(what);
    std::string bytes;
    {
      std::ifstream in(file, std::ios::binary);
      bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    damage(bytes);
    std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
    PatchRadiosityStats s;
    expectSame(solveWith(scene, dir, s, estimator), reference);
    EXPECT_FALSE(s.cacheLoaded);
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_NE(s.warnings[0].find(expectedReason), std::string::npos) << s.warnings[0];
    PatchRadiosityStats repaired;
    solveWith(scene, dir, repaired, estimator);
    EXPECT_TRUE(repaired.cacheLoaded);
  };
  damageAndCheck(
      "truncated", [](std::string& b) { b.resize(b.size() / 2); }, "truncated");
  damageAndCheck(
      "byte flipped", [](std::string& b) { b[b.size() / 2] ^= 0x5a; }, "corrupt");
  damageAndCheck(
      "old version", [](std::string& b) { b[8] = 0; }, "version");
  damageAndCheck(
      "foreign", [](std::string& b) { b.replace(0, 8, "NOTOURS!"); }, "not a form-factor");
  // A forged file whose checksum matches: its last form factor (a whole table's last value, a
  // master table's last hit weight, both just before the checksum) raised to 50. Before, a
  // table accepted so diverged: 1000 sweeps, a residual of NaN, inf in the outputs.
  damageAndCheck(
      "forged",
      [](std::string& b) {
        const float forged = 50.0f;
        std::memcpy(b.data() + b.size() - 12, &forged, 4);
        const uint64_t sum = checksum(b.data(), b.size() - 8);
        std::memcpy(b.data() + b.size() - 8, &sum, 8);
      },
      estimator == PatchFormFactorEstimator::Hemisphere ? "row summing above" : "sums to");
  // A directory or a FIFO where the file should be: a warning and a recompute, never a hang.
  for (const bool fifo : {false, true}) {
    fs::remove(file);
    if (fifo)
      ASSERT_EQ(mkfifo(file.c_str(), 0600), 0);
    else
      fs::create_directories(file);
    PatchRadiosityStats s;
    expectSame(solveWith(scene, dir, s, estimator), reference);
    EXPECT_FALSE(s.cacheLoaded);
    ASSERT_FALSE(s.warnings.empty());
    EXPECT_NE(s.warnings[0].find("unreadable"), std::string::npos) << s.warnings[0];
    fs::remove_all(file);
  }
  fs::remove_all(dir);
}

TEST(PatchCache, SecondRunLoadsAndBadMasterTablesAreRecomputed) {
  expectSecondRunLoadsAndBadFilesRecomputed(PatchFormFactorEstimator::Hemisphere);
}

TEST(PatchCache, SecondRunLoadsAndBadWholeTablesAreRecomputed) {
  expectSecondRunLoadsAndBadFilesRecomputed(PatchFormFactorEstimator::Pairwise);
}

// Stopped (as Ctrl-C does) half way through casting its form factors, a solve keeps the rows
// cast so far in the cache; solved again, it casts only the rest and gets the answer of a solve
// never stopped, bit for bit (each row has its own random stream).
TEST(PatchCache, RowsCastBeforeAStopAreKept) {
  const fs::path dir = fs::path(::testing::TempDir()) / "radiosity_patch_cache_stop";
  fs::remove_all(dir);
  const Scene scene = loadScene("cornell");
  PatchRadiositySettings settings;
  settings.targetPatches = 400;
  settings.cacheDir = dir.string();
  bool stopped = false;
  try {
    PatchRadiosity(scene, settings, [](double f) { return f < 0.5; });
  } catch (const Cancelled& e) {
    stopped = true;
    EXPECT_NE(std::string(e.what()).find("rows cast so far are kept"), std::string::npos)
        << e.what();
  }
  ASSERT_TRUE(stopped);
  const PatchRadiosity resumed(scene, settings);
  settings.cacheDir.clear();
  const PatchRadiosity whole(scene, settings);
  EXPECT_GT(resumed.stats().rowsReused, 0u);
  EXPECT_LT(resumed.stats().rowsComputed, whole.stats().rowsComputed);
  ASSERT_EQ(resumed.elementCount(), whole.elementCount());
  for (size_t p = 0; p < whole.elementCount(); ++p)
    ASSERT_EQ(resumed.element(p).radiosity, whole.element(p).radiosity) << "patch " << p;
  fs::remove_all(dir);
}

// Smooth shading: radiance is continuous across patch boundaries (a point just either side of an
// edge gives nearly the same), and flat shading gives each patch its own value.
TEST(PatchRadiance, SmoothAcrossPatchEdges) {
  const Scene scene = smallRoom();
  PatchRadiositySettings settings;
  settings.patchSize = 0.125f;
  const PatchRadiosity smooth(scene, settings);
  settings.shading = PatchShading::Flat;
  const PatchRadiosity flat(scene, settings);
  // The floor (face 2, y = 0, facing +y): an edge of the 8 x 8 grid at x = 0.5.
  uint32_t triangle = 0;
  while (scene.triangleFace[triangle] != 2) ++triangle;
  auto at = [&](const PatchRadiosity& r, float x) {
    return r.radiance({Vec3(x, 0.0f, 0.3f), Vec3(0, 1, 0), triangle, true});
  };
  const float eps = 1e-4f;
  EXPECT_NEAR(at(smooth, 0.5f - eps).g, at(smooth, 0.5f + eps).g, 1e-3f * at(smooth, 0.5f).g);
  EXPECT_GT(std::abs(at(flat, 0.5f - eps).g - at(flat, 0.5f + eps).g), 1e-3f * at(flat, 0.5f).g);
  EXPECT_EQ(smooth.radiance({Vec3(0.5f, 0.0f, 0.3f), Vec3(0, 1, 0), triangle, false}), Color(0.0f));
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

// A threshold drops small form factors but not the light they carried (FormFactorTable::
// applyThreshold): at --ff-threshold 0.01 the Cornell box drops 82% of its form-factor sum
// (before: the floor went black), yet absorbs within 2% of what the full table absorbs, per
// channel (measured: -0.2%, -1.3%, -1.1%), and says that it moved light.
TEST(PatchThreshold, KeepsTheEnergyBalanceAndWarns) {
  const Scene scene = loadScene("cornell");
  PatchRadiositySettings settings;
  settings.cacheDir.clear();
  const PatchRadiosity full(scene, settings);
  settings.formFactorThreshold = 0.01f;
  const PatchRadiosity thresholded(scene, settings);
  EXPECT_EQ(full.stats().droppedSumFraction, 0.0);
  EXPECT_TRUE(full.stats().warnings.empty());
  EXPECT_GT(thresholded.stats().droppedSumFraction, 0.5);
  EXPECT_LT(thresholded.stats().nonZeros, full.stats().nonZeros / 5);
  EXPECT_GT(thresholded.stats().rowsDroppingOverOnePercent, 0u);
  ASSERT_EQ(thresholded.stats().warnings.size(), 1u);
  EXPECT_NE(thresholded.stats().warnings[0].find("--ff-threshold 0.01"), std::string::npos);
  const Color a = absorbedPower(scene, full.objectRadiometry());
  const Color b = absorbedPower(scene, thresholded.objectRadiometry());
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(b[c], a[c], 0.02 * a[c]) << "channel " << c;

  // Its cache is read back (a redirected entry may exceed 1; the cache once refused those).
  const fs::path dir = fs::path(::testing::TempDir()) / "radiosity_threshold_cache";
  fs::remove_all(dir);
  settings.cacheDir = dir.string();
  const PatchRadiosity first(scene, settings), again(scene, settings);
  EXPECT_FALSE(first.stats().cacheLoaded);
  EXPECT_TRUE(again.stats().cacheLoaded);
  EXPECT_EQ(again.stats().warnings, first.stats().warnings);
  EXPECT_EQ(again.objectRadiometry()[0].meanRadiosity, first.objectRadiometry()[0].meanRadiosity);
}

// The threshold as rows of outgoing light: entries below it go, but the row's largest, and the
// rest are scaled to the row's sum.
TEST(PatchThreshold, RowKeepsItsSumAndItsLargestEntry) {
  std::vector<FormFactorEntry> row{{0, 0.004f}, {3, 0.02f}, {5, 0.006f}, {9, 0.01f}};
  const RowThresholding sums = thresholdRow(row, 0.008f);
  EXPECT_NEAR(sums.total, 0.04, 1e-7);
  EXPECT_NEAR(sums.kept, 0.03, 1e-7);
  ASSERT_EQ(row.size(), 2u);
  EXPECT_EQ(row[0].column, 3u);
  EXPECT_NEAR(row[0].value + row[1].value, 0.04f, 1e-7f);
  EXPECT_NEAR(row[0].value / row[1].value, 2.0f, 1e-5f);

  std::vector<FormFactorEntry> small{{1, 0.001f}, {2, 0.003f}};  // all below: the largest stays
  thresholdRow(small, 0.01f);
  ASSERT_EQ(small.size(), 1u);
  EXPECT_EQ(small[0].column, 2u);
  EXPECT_NEAR(small[0].value, 0.004f, 1e-7f);
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

// A small tile just above a large floor, one patch each, and a lamp above both: the floor's 256
// rays find the tile once or not at all, its estimate of their exchange is noisy where the
// tile's own (nearly all of its rays land on the floor) is sure. The plain mean of the two let
// the tile's row sum to 1.08 for some seeds (light made from nothing); weighted by inverse
// variance the table keeps reciprocity and the tile's row its own sum (within 2%, at most 1.002).
TEST(PatchTable, SymmetrizationTrustsTheSurerEstimate) {
  SceneBuilder b("tile over floor");
  const uint32_t grey = b.addMaterial({"grey", Color(0.5f), Color(0.0f), false});
  const uint32_t lamp = b.addMaterial({"lamp", Color(0.0f), Color(1.0f), false});
  test::addQuadFacing(b, test::axisSquare(Vec3(0.0f), 1, 1.0f), Vec3(0, 1, 0), grey,
                      b.addObject("floor"));
  test::addQuadFacing(b, test::axisSquare(Vec3(0.0f, 0.02f, 0.0f), 1, 0.1f), Vec3(0, -1, 0), grey,
                      b.addObject("tile"));
  test::addQuadFacing(b, test::axisSquare(Vec3(0.0f, 2.0f, 0.0f), 1, 1.0f), Vec3(0, -1, 0), lamp,
                      b.addObject("lamp"));
  const Scene scene = b.build();
  const PatchMesh mesh(scene, {2.0f, 0});
  ASSERT_EQ(mesh.size(), 3u);
  const RayCaster caster(scene);
  FormFactorSettings ff;
  ff.rays = 256;
  std::vector<float> area;
  for (const Patch& p : mesh.patches()) area.push_back(p.area);
  const uint32_t tile = mesh.patches()[1].object == 1 ? 1 : 0;
  for (uint64_t seed = 1; seed <= 8; ++seed) {
    ff.seed = seed;
    FormFactorRows rows = estimateFormFactors(mesh, caster, ff, {});
    FormFactorTable table = FormFactorTable::fromRows(std::move(rows));
    const double own = table.rowSum(tile);
    table.symmetrize(area);
    EXPECT_NEAR(table.rowSum(tile), own, 0.02 * own) << "seed " << seed;
    EXPECT_LE(table.rowSum(tile), 1.01) << "seed " << seed;
  }
}

}  // namespace
}  // namespace rad
