// The table of a changed quadtree made from the table before (patch/table_update.h) is the one
// assembled anew from every row, bit for bit; where the emitters' patches change, it declines.
#include "patch/table_update.h"

#include <gtest/gtest.h>
#include <radiosity/ray_caster.h>
#include <radiosity/scene_loader.h>

#include <algorithm>
#include <vector>

namespace rad {
namespace {

constexpr int kLevels = 2;

struct Fixture {
  Scene scene = loadScene("cornell");
  PatchMesh base{scene, PatchMeshSettings{0.0f, 400}};
  RayCaster caster{scene};
  MasterFormFactorTable master{kLevels, 64, 1};
  std::vector<uint32_t> basePatchOf;

  Fixture() {
    basePatchOf.assign(base.nodes().size(), kNoPatch);
    for (uint32_t p = 0; p < base.size(); ++p) basePatchOf[base.patches()[p].node] = p;
  }

  // The emitters' patches as exact columns, as the patch method chooses them.
  FormFactorSettings settingsFor(const PatchMesh& mesh) const {
    FormFactorSettings ff;
    ff.rays = 64;
    for (uint32_t p = 0; p < mesh.size(); ++p)
      if (maxComponent(scene.materials[mesh.patches()[p].material].emission) > 0.0f)
        ff.exactColumns.push_back(p);
    return ff;
  }
  static std::vector<float> areas(const PatchMesh& mesh) {
    std::vector<float> a;
    for (const Patch& p : mesh.patches()) a.push_back(p.area);
    return a;
  }
  FormFactorTable assembled(const PatchMesh& mesh) {
    FormFactorTable t = FormFactorTable::fromRows(
        master.rowsFor(mesh, caster, basePatchOf, settingsFor(mesh), {}).rows);
    t.symmetrize(areas(mesh));
    return t;
  }
  std::optional<FormFactorTable> updated(const PatchMesh& before, const FormFactorTable& table,
                                         const PatchMesh& mesh) {
    const FormFactorSettings ff = settingsFor(mesh);
    std::optional<PatchMatch> match = matchPatches(before, mesh, kLevels);
    EXPECT_TRUE(match.has_value());
    const MasterFormFactorTable::Rows rows =
        master.rowsFor(mesh, caster, basePatchOf, ff, {}, match->fresh());
    return updatedTable({before, table, settingsFor(before).exactColumns}, mesh, std::move(*match),
                        ff.exactColumns, rows, kLevels);
  }
  // The base mesh with the non-emitting patches whose centroids pass `where` split, twice
  // where `twice` passes too.
  template <class Where, class Twice>
  PatchMesh refined(const Where& where, const Twice& twice) const {
    PatchMesh mesh = base;
    auto split = [&](const auto& chosen) {
      std::vector<uint32_t> patches;
      for (uint32_t p = 0; p < mesh.size(); ++p) {
        const Patch& patch = mesh.patches()[p];
        if (maxComponent(scene.materials[patch.material].emission) <= 0.0f &&
            chosen(patch.centroid))
          patches.push_back(p);
      }
      mesh.refine(patches);
    };
    split(where);
    split(twice);
    return mesh;
  }
};

void expectSameTable(const FormFactorTable& a, const FormFactorTable& b) {
  ASSERT_EQ(a.rows(), b.rows());
  ASSERT_EQ(a.nonZeros(), b.nonZeros());
  EXPECT_TRUE(std::ranges::equal(a.offsetArray(), b.offsetArray()));
  EXPECT_TRUE(std::ranges::equal(a.columnArray(), b.columnArray()));
  EXPECT_TRUE(std::ranges::equal(a.valueArray(), b.valueArray()));
}

TEST(TableUpdate, EqualsTheTableAssembledAnewBitForBit) {
  Fixture f;
  // A band of the box split (twice near its middle) as a beam would, then the band moved: some
  // patches split, some merged, some split further; the emitter's patches unchanged.
  // (The box spans 0-556 in x.)
  const PatchMesh first = f.refined([](const Vec3& c) { return c.x < 90.0f; },
                                    [](const Vec3& c) { return c.x > 30.0f && c.x < 60.0f; });
  const PatchMesh second = f.refined([](const Vec3& c) { return c.x > 60.0f && c.x < 150.0f; },
                                     [](const Vec3& c) { return c.x > 90.0f && c.x < 120.0f; });
  ASSERT_NE(first.size(), second.size());
  const std::vector<uint8_t> fresh = matchPatches(first, second, kLevels)->fresh();
  const size_t changed = size_t(std::count(fresh.begin(), fresh.end(), 1));
  ASSERT_GT(changed, 20u);
  ASSERT_LT(changed, second.size() / 2);  // most rows kept
  const FormFactorTable before = f.assembled(first);
  const std::optional<FormFactorTable> updated = f.updated(first, before, second);
  ASSERT_TRUE(updated.has_value());
  expectSameTable(*updated, f.assembled(second));
  // And back: the way a swinging light returns.
  const std::optional<FormFactorTable> back = f.updated(second, *updated, first);
  ASSERT_TRUE(back.has_value());
  expectSameTable(*back, before);
}

TEST(TableUpdate, DeclinesWhenAnEmittersPatchChanged) {
  Fixture f;
  const PatchMesh first =
      f.refined([](const Vec3& c) { return c.x < 140.0f; }, [](const Vec3&) { return false; });
  PatchMesh second = first;
  const std::vector<uint32_t> emitters = f.settingsFor(second).exactColumns;
  ASSERT_FALSE(emitters.empty());
  second.refine(std::vector<uint32_t>{emitters.front()});
  const FormFactorTable before = f.assembled(first);
  EXPECT_FALSE(f.updated(first, before, second).has_value());
}

}  // namespace
}  // namespace rad
