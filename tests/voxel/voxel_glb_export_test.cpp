// The voxel solution baked into the scene's triangles as binary glTF: read back with tinygltf,
// it must cover the scene exactly (area, winding, one node per object), be cut finely enough to
// follow the voxels, show what the renderer shows, and carry each object's light: the
// area-weighted mean of its baked radiance agrees with the mean over its voxel sides.
#include <gtest/gtest.h>
#include <radiosity/voxel_radiosity.h>

#include <algorithm>
#include <filesystem>
#include <glm/gtc/constants.hpp>
#include <glm/gtx/component_wise.hpp>

#include "output/glb_reader.h"
#include "voxel/voxel_test_scenes.h"

namespace fs = std::filesystem;

namespace rad {
namespace {

Vec3 at(const std::vector<float>& v, uint32_t i) {
  return Vec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
}

TEST(VoxelGlbExport, BakesTheSolutionIntoTheSceneTriangles) {
  // The lit cube room, its lamp dim enough that no colour clamps.
  const Scene scene = test::litCubeRoom(Color(0.2f), Color(0.6f));
  VoxelRadiositySettings settings;
  settings.voxelSize = 1.0f / 16.0f;
  settings.sphereRadius = 8;
  settings.iterations = 4;
  const VoxelRadiosity solution(scene, settings);
  const std::vector<ObjectRadiometry> sides = solution.objectRadiometry();

  const fs::path dir = fs::path(::testing::TempDir()) / "radiosity_voxel_glb";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path file = dir / "room.glb";
  solution.exportGlb(file.string());
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  const tinygltf::Model model = test::loadGlb(file);

  ASSERT_EQ(model.nodes.size(), scene.objects.size());
  double sceneArea = 0.0;
  for (const Face& f : scene.faces) sceneArea += f.area;
  double area = 0.0;
  size_t probes = 0;
  for (size_t o = 0; o < model.nodes.size(); ++o) {
    const tinygltf::Node& node = model.nodes[o];
    EXPECT_EQ(node.name, scene.objects[o].name);
    const Face& face = *std::find_if(scene.faces.begin(), scene.faces.end(),
                                     [&](const Face& f) { return f.object == o; });
    // Front and back pieces: area and radiance times area.
    double sideArea[2] = {0.0, 0.0};
    Vec3d radianceTimesArea[2] = {Vec3d(0.0), Vec3d(0.0)};
    for (const tinygltf::Primitive& prim : model.meshes.at(size_t(node.mesh)).primitives) {
      EXPECT_FALSE(model.materials.at(size_t(prim.material)).doubleSided) << node.name;
      const auto positions = test::readAccessor<float>(model, prim.attributes.at("POSITION"), 3);
      const auto normals = test::readAccessor<float>(model, prim.attributes.at("NORMAL"), 3);
      const auto colors = test::readAccessor<float>(model, prim.attributes.at("COLOR_0"), 3);
      const auto indices = test::readAccessor<uint32_t>(model, prim.indices, 1);
      ASSERT_EQ(colors.size(), positions.size());
      for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const Vec3 a = at(positions, indices[t]), b = at(positions, indices[t + 1]);
        const Vec3 c = at(positions, indices[t + 2]);
        const Vec3 n = glm::cross(b - a, c - a);
        const int side = glm::dot(n, face.normal) > 0.0f ? 0 : 1;
        // Wound to face the way its vertex normals point.
        EXPECT_GT(glm::dot(n, at(normals, indices[t])), 0.0f);
        // Cut to the voxel size: the baked light can follow what the voxels resolve.
        const float longest =
            std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
        EXPECT_LE(longest, settings.voxelSize * 1.0001f);
        const double triangleArea = 0.5 * glm::length(n);
        sideArea[side] += triangleArea;
        radianceTimesArea[side] +=
            triangleArea / 3.0 *
            Vec3d(at(colors, indices[t]) + at(colors, indices[t + 1]) + at(colors, indices[t + 2]));
      }
      // Probes: a vertex's colour is the radiance the renderer shows there, from its side.
      for (uint32_t v = 0; 3 * v < positions.size(); v += 17, ++probes) {
        const bool front = glm::dot(at(normals, v), face.normal) > 0.0f;
        const Color expected =
            solution.radiance({at(positions, v), face.normal, face.firstTriangle, front});
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(at(colors, v)[ch], expected[ch], 1e-5f);
      }
    }
    area += sideArea[0];
    EXPECT_NEAR(sideArea[0], face.area, 1e-4 * face.area);
    // The two-sided wall's back, outside the closed room, gets no light; the rest has no back.
    EXPECT_NEAR(sideArea[1], o == 0 ? face.area : 0.0, 1e-4 * face.area);
    if (o == 0) {
      EXPECT_LT(glm::compMax(radianceTimesArea[1]), 1e-6) << "light outside the room";
    }
    // The mean over the voxel sides of the object (B / pi), an independent reduction of the
    // solution: interpolation between voxels moves it by under 1% here (2% allowed).
    const Vec3d baked = radianceTimesArea[0] / sideArea[0];
    const Vec3d expected = Vec3d(sides[o].meanRadiosity) / glm::pi<double>();
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_NEAR(baked[ch], expected[ch], 0.02 * expected[ch] + 1e-4)
          << node.name << " channel " << ch;
  }
  EXPECT_NEAR(area, sceneArea, 1e-4 * sceneArea);
  EXPECT_GE(probes, 100u);
}

TEST(VoxelGlbExport, TexturedFacesCarryIrradianceUnderTheirTexture) {
  // The pieces of the textured quad go out under its texture, coloured with the solution's H /
  // pi, as the patch method's export.
  const Scene scene = test::litTexturedQuad();
  VoxelRadiositySettings settings;
  settings.voxelSize = 0.1f;
  settings.sphereRadius = 4;
  settings.iterations = 1;
  const VoxelRadiosity solution(scene, settings);
  const fs::path dir = fs::path(::testing::TempDir()) / "radiosity_voxel_textured_glb";
  fs::remove_all(dir);
  fs::create_directories(dir);
  solution.exportGlb((dir / "quad.glb").string());
  test::expectQuadUnderItsTexture(test::loadGlb(dir / "quad.glb"), scene, solution);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rad
