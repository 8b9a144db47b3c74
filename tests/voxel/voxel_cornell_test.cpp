// The voxel method against the reference path tracer on the Cornell box.
#include <radiosity/path_tracer.h>
#include <radiosity/scene_loader.h>
#include <radiosity/voxel_radiosity.h>

#include <gtest/gtest.h>

#include <map>

namespace rad {
namespace {

TEST(VoxelCornell, SurfaceMeansMatchThePathTracer) {
  const Scene scene = loadScene("cornell");
  // Reference: the path tracer's per-object means, 400 points x 256 irradiance paths each
  // (standard error well under 1% per object).
  PathTracerSettings reference;
  reference.samplesPerPixel = 256;
  reference.seed = 5;
  std::map<std::string, ObjectRadiometry> expected;
  for (const ObjectRadiometry& o : estimateObjectRadiometry(scene, 400, reference)) expected[o.name] = o;

  // A coarse solve to keep the test fast (20k voxels, R = 12: 1,250 directions); the default
  // resolution is closer still (docs/ARCHITECTURE.md has the measured numbers).
  VoxelRadiositySettings settings;
  settings.targetVoxels = 20000;
  settings.sphereRadius = 12;
  settings.directSamples = 32;
  const VoxelRadiosity solution(scene, settings);
  for (const ObjectRadiometry& o : solution.objectRadiometry()) {
    if (o.name == "light") continue;  // its radiosity is its emission, an input
    const ObjectRadiometry& ref = expected.at(o.name);
    EXPECT_NEAR(o.area, ref.area, 0.01 * ref.area) << o.name;
    for (int c = 0; c < 3; ++c) {
      if (ref.meanRadiosity[c] < 0.02f) continue;  // a channel the paint absorbs almost fully
      EXPECT_NEAR(o.meanRadiosity[c], ref.meanRadiosity[c], 0.07 * ref.meanRadiosity[c])
          << o.name << " channel " << c;
    }
  }
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

TEST(VoxelCornell, SpotLightReachesVoxelsThroughTheFirstShot) {
  const Scene scene = loadScene("cornell-spot");
  PathTracerSettings reference;
  reference.samplesPerPixel = 128;
  std::map<std::string, ObjectRadiometry> expected;
  for (const ObjectRadiometry& o : estimateObjectRadiometry(scene, 200, reference)) expected[o.name] = o;

  VoxelRadiositySettings settings;
  settings.targetVoxels = 8000;
  settings.sphereRadius = 8;
  settings.directSamples = 16;
  const VoxelRadiosity lit(scene, settings);
  EXPECT_TRUE(lit.stats().warnings.empty());
  for (const ObjectRadiometry& o : lit.objectRadiometry()) {
    if (o.name != "floor" && o.name != "back_wall") continue;
    // Coarse (8k voxels, R = 8) yet within 10% of the path tracer (200 points x 128 paths).
    EXPECT_NEAR(o.meanRadiosity.g, expected.at(o.name).meanRadiosity.g,
                0.1 * expected.at(o.name).meanRadiosity.g) << o.name;
  }

  settings.directFirstShot = false;  // the sweeps alone cannot see a point light
  const VoxelRadiosity dark(scene, settings);
  ASSERT_EQ(dark.stats().warnings.size(), 1u);
  for (const ObjectRadiometry& o : dark.objectRadiometry()) EXPECT_EQ(o.meanRadiosity.g, 0.0f) << o.name;
}

}  // namespace
}  // namespace rad
