// Baking a SurfaceRadiance into the scene's triangles: the cut covers each triangle exactly, no
// piece is longer than asked, a sliver becomes a row of pieces rather than a grid, and every
// vertex carries the radiance at its own position.
#include <gtest/gtest.h>
#include <radiosity/baked_mesh.h>
#include <radiosity/scene_builder.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace rad {
namespace {

// Radiance that varies across space and between the sides, so that a vertex given another's
// colour shows.
Color linearRadiance(const Vec3& point, uint32_t triangle, bool front) {
  return Color(point.x, point.y, float(triangle) + (front ? 0.0f : 100.0f));
}
class LinearRadiance : public SurfaceRadiance {
 public:
  Color radiance(const SurfaceHit& hit) const override {
    return linearRadiance(hit.point, hit.triangle, hit.frontFace);
  }
};

Scene twoTriangles() {
  SceneBuilder b("shapes");
  const uint32_t m = b.addMaterial({"white", Color(0.5f), Color(0.0f), false});
  const uint32_t twoSided = b.addMaterial({"card", Color(0.5f), Color(0.0f), true});
  // A right triangle of legs 1 and a sliver 10 long and 0.01 wide, in the z = 0 plane.
  const uint32_t a = b.addVertex({0, 0, 0}, "a"), c = b.addVertex({1, 0, 0}, "c");
  const uint32_t d = b.addVertex({0, 1, 0}, "d");
  const uint32_t s0 = b.addVertex({0, 2, 0}, "s0"), s1 = b.addVertex({10, 2, 0}, "s1");
  const uint32_t s2 = b.addVertex({10, 2.01f, 0}, "s2");
  const std::array<uint32_t, 3> right{a, c, d}, sliver{s0, s1, s2};
  b.addPolygon(right, m, b.addObject("right"), "right");
  b.addPolygon(sliver, twoSided, b.addObject("sliver"), "sliver");
  return b.build();
}

double triangleArea(const Vec3& a, const Vec3& b, const Vec3& c) {
  return 0.5 * glm::length(glm::cross(b - a, c - a));
}

TEST(BakedMesh, CutsEachTriangleIntoPiecesNoLongerThanAsked) {
  const Scene scene = twoTriangles();
  const LinearRadiance radiance;
  const float maxEdge = 0.1f;
  const LitMesh mesh = bakeSurfaceRadiance(scene, radiance, maxEdge);
  ASSERT_EQ(mesh.groups.size(), 2u);
  for (size_t g = 0; g < 2; ++g) {
    const LitMeshGroup& group = mesh.groups[g];
    EXPECT_EQ(group.name, scene.objects[g].name);
    const Face& face = scene.faces[g];
    double area[2] = {0.0, 0.0};  // front, back
    for (uint32_t t = group.firstTriangle; t < group.firstTriangle + group.triangleCount; ++t) {
      const Vec3 a = mesh.positions[mesh.indices[3 * t]];
      const Vec3 b = mesh.positions[mesh.indices[3 * t + 1]];
      const Vec3 c = mesh.positions[mesh.indices[3 * t + 2]];
      EXPECT_LE(std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)}),
                maxEdge * 1.0001f);
      const bool front = glm::dot(glm::cross(b - a, c - a), face.normal) > 0.0f;
      area[front ? 0 : 1] += triangleArea(a, b, c);
      for (int k = 0; k < 3; ++k) {
        // Wound to face the way of its side, coloured with that side's radiance.
        const uint32_t v = mesh.indices[3 * t + size_t(k)];
        EXPECT_EQ(mesh.normals[v], front ? face.normal : -face.normal);
        EXPECT_EQ(mesh.colors[v], linearRadiance(mesh.positions[v], face.firstTriangle, front));
      }
    }
    EXPECT_NEAR(area[0], face.area, 1e-4 * face.area);
    // Only the two-sided sliver has a back.
    EXPECT_NEAR(area[1], g == 1 ? face.area : 0.0, 1e-4 * face.area);
  }
  // The right triangle of area 1/2 in pieces of about maxEdge^2 / 4 (halved squares of side
  // maxEdge / sqrt 2): 200 when cut to the limit, at most twice that.
  EXPECT_GE(mesh.groups[0].triangleCount, 200u);
  EXPECT_LE(mesh.groups[0].triangleCount, 400u);
  // The sliver, 10 long and 0.01 wide: a strip, two rows of steps of half the limit (about
  // 400 pieces a side), not the 100^2 of a regular grid nor the fan of bisection (2,187).
  EXPECT_GE(mesh.groups[1].triangleCount, 2 * 200u);
  EXPECT_LE(mesh.groups[1].triangleCount, 2 * 450u);
}

TEST(BakedMesh, RefusesACutTooFineBeforeMakingIt) {
  const Scene scene = twoTriangles();
  const LinearRadiance radiance;
  EXPECT_THROW(bakeSurfaceRadiance(scene, radiance, 1e-4f), std::invalid_argument);
  EXPECT_THROW(bakeSurfaceRadiance(scene, radiance, 0.0f), std::invalid_argument);
}

}  // namespace
}  // namespace rad
