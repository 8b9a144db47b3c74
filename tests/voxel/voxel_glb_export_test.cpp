// The voxel solution baked into the scene's triangles as binary glTF: read back with tinygltf,
// it must cover the scene exactly (area, winding, one node per object), be cut finely enough to
// follow the voxels, show what the renderer shows, and carry each object's light: the
// area-weighted mean of its baked radiance agrees with the mean over its voxel sides.
#include <gtest/gtest.h>
#include <radiosity/voxel_radiosity.h>

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <filesystem>

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
    double objectArea = 0.0;
    Vec3d radianceTimesArea(0.0);
    for (const tinygltf::Primitive& prim : model.meshes.at(size_t(node.mesh)).primitives) {
      EXPECT_EQ(model.materials.at(size_t(prim.material)).doubleSided, o == 0) << node.name;
      const auto positions = test::readAccessor<float>(model, prim.attributes.at("POSITION"), 3);
      const auto colors = test::readAccessor<float>(model, prim.attributes.at("COLOR_0"), 3);
      const auto indices = test::readAccessor<uint32_t>(model, prim.indices, 1);
      ASSERT_EQ(colors.size(), positions.size());
      for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const Vec3 a = at(positions, indices[t]), b = at(positions, indices[t + 1]);
        const Vec3 c = at(positions, indices[t + 2]);
        const Vec3 n = glm::cross(b - a, c - a);
        EXPECT_GT(glm::dot(n, face.normal), 0.0f) << "triangle wound against the front side";
        // Cut to the voxel size: the baked light can follow what the voxels resolve.
        const float longest = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
        EXPECT_LE(longest, settings.voxelSize * 1.0001f);
        const double triangleArea = 0.5 * glm::length(n);
        objectArea += triangleArea;
        radianceTimesArea += triangleArea / 3.0 *
                             Vec3d(at(colors, indices[t]) + at(colors, indices[t + 1]) +
                                   at(colors, indices[t + 2]));
      }
      // Probes: a vertex's colour is the radiance the renderer shows there.
      for (uint32_t v = 0; 3 * v < positions.size(); v += 17, ++probes) {
        const Color expected = solution.radiance({at(positions, v), face.normal,
                                                  face.firstTriangle, true});
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(at(colors, v)[ch], expected[ch], 1e-5f);
      }
    }
    area += objectArea;
    // The mean over the voxel sides of the object (B / pi), an independent reduction of the
    // solution: interpolation between voxels moves it by under 1% here (2% allowed).
    const Vec3d baked = radianceTimesArea / objectArea;
    const Vec3d expected = Vec3d(sides[o].meanRadiosity) / glm::pi<double>();
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_NEAR(baked[ch], expected[ch], 0.02 * expected[ch] + 1e-4)
          << node.name << " channel " << ch;
  }
  EXPECT_NEAR(area, sceneArea, 1e-4 * sceneArea);
  EXPECT_GE(probes, 100u);
}

}  // namespace
}  // namespace rad
