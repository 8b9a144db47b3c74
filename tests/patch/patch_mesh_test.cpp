// The quadtree patch mesh: counts, tree links, welding and point location.
#include <gtest/gtest.h>
#include <radiosity/scene_loader.h>

#include <set>

#include "core/rng.h"
#include "patch_test_scenes.h"

namespace rad {
namespace {

TEST(PatchMesh, SubdividesQuadsIntoQuadsAndWeldsCorners) {
  const Scene cube = test::uniformCube(Color(0.5f), Color(0.0f));
  const PatchMesh mesh(cube, {0.25f, 0});
  // A unit face split until edges are <= 0.25: 4 x 4 quads; 5 x 5 corners per face, not welded
  // across the 90-degree edges (creases).
  ASSERT_EQ(mesh.size(), 6u * 16u);
  EXPECT_EQ(mesh.vertices().size(), 6u * 25u);
  double area = 0.0;
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    EXPECT_TRUE(mesh.nodeOf(p).quad);
    EXPECT_NEAR(mesh.patches()[p].area, 1.0 / 16.0, 1e-6);
    area += mesh.patches()[p].area;
  }
  EXPECT_NEAR(area, 6.0, 1e-5);
  // The tree: ids are indices, children point back to their parent, leaves are the patches.
  std::set<uint32_t> leaves;
  for (uint32_t id = 0; id < mesh.nodes().size(); ++id) {
    const PatchNode& n = mesh.nodes()[id];
    if (n.leaf()) {
      ASSERT_NE(n.patch, kNoPatch);
      EXPECT_EQ(mesh.patches()[n.patch].node, id);
      leaves.insert(n.patch);
      continue;
    }
    for (uint32_t k = 0; k < 4; ++k) {
      EXPECT_EQ(mesh.nodes()[n.firstChild + k].parent, id);
      EXPECT_EQ(mesh.nodes()[n.firstChild + k].depth, n.depth + 1);
    }
  }
  EXPECT_EQ(leaves.size(), mesh.size());
  EXPECT_EQ(mesh.nodes().size(), 6u * (1 + 4 + 16));
}

TEST(PatchMesh, SplitsTrianglesIntoFour) {
  SceneBuilder b("triangle");
  const uint32_t m = b.addMaterial(test::grey(0.5f));
  const uint32_t o = b.addObject("t");
  std::array<uint32_t, 3> ids{b.addVertex(Vec3(0, 0, 0), "t"), b.addVertex(Vec3(1, 0, 0), "t"),
                              b.addVertex(Vec3(0, 1, 0), "t")};
  b.addPolygon(ids, m, o, "t");
  const Scene s = b.build();
  const PatchMesh mesh(s, {0.3f, 0});  // longest edge sqrt(2): three halvings to 0.18
  EXPECT_EQ(mesh.size(), 64u);
  EXPECT_EQ(mesh.vertices().size(), 45u);  // (2^3 + 1)(2^3 + 2) / 2 welded corners
  for (uint32_t p = 0; p < mesh.size(); ++p) {
    EXPECT_FALSE(mesh.nodeOf(p).quad);
    EXPECT_NEAR(mesh.patches()[p].area, 0.5 / 64, 1e-7);
  }
}

TEST(PatchMesh, PatchCountTargetsAreMet) {
  const Scene cornell = loadScene("cornell");
  const PatchMesh mesh(cornell, {0.0f, 4000});
  EXPECT_GE(mesh.size(), 4000u);
  EXPECT_LE(mesh.size(), 16000u);
}

// Every located point lies inside its patch, and the corner weights reproduce it.
TEST(PatchMesh, LocatesPointsOnTheirPatch) {
  const Scene cornell = loadScene("cornell");
  const PatchMesh mesh(cornell, {40.0f, 0});
  Rng rng(3, 4);
  for (uint32_t t = 0; t < cornell.triangles.size(); ++t)
    for (int k = 0; k < 50; ++k) {
      const UVec3 tri = cornell.triangles[t];
      const float s = std::sqrt(rng.uniform()), v = rng.uniform();
      const Vec3 p = (1 - s) * cornell.positions[tri.x] + s * (1 - v) * cornell.positions[tri.y] +
                     s * v * cornell.positions[tri.z];
      const PatchMesh::Location loc = mesh.locate(t, true, p);
      ASSERT_NE(loc.patch, kNoPatch);
      std::array<Vec3, 4> c;
      const int n = mesh.corners(loc.patch, c);
      Vec3 q(0.0f);
      for (int i = 0; i < n; ++i) q += loc.weights[i] * c[i];
      EXPECT_LT(glm::distance(p, q), 1e-2f) << "triangle " << t;
      EXPECT_EQ(mesh.patches()[loc.patch].face, cornell.triangleFace[t]);
      EXPECT_EQ(mesh.locate(t, false, p).patch, kNoPatch);  // one-sided: no back patches
    }
}

}  // namespace
}  // namespace rad
