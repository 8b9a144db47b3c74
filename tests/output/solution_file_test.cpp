// Solution files: a saved and loaded solution is the solution it was (the same picture bit for
// bit, the same light groups); a file that is cut, corrupt, of another version, method, scene or
// lights is refused with a message that says which.
#include <gtest/gtest.h>
#include <radiosity/error.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/scene_loader.h>
#include <radiosity/solution_file.h>
#include <radiosity/surface_radiance.h>
#include <radiosity/voxel_radiosity.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/binary_io.h"
#include "lighting/light_test_scenes.h"

namespace rad {
namespace {

namespace fs = std::filesystem;

fs::path tempFile(const std::string& name) {
  return fs::path(::testing::TempDir()) / ("solution_file_" + name);
}

std::string bytesOf(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void writeBytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// The Cornell box with its lamp and a spot of group "spot", whose beam refines the patches.
Scene boxWithSpot() {
  Scene scene = loadScene("cornell");
  Light spot = test::downSpot(Vec3(300.0f, 500.0f, 250.0f), Color(8e4f), 20.0f, 30.0f);
  spot.group = "spot";
  scene.lights.push_back(spot);
  return scene;
}

Image picture(const Scene& scene, const SurfaceRadiance& solution) {
  Camera camera = scene.cameraOrDefault();
  camera.width = camera.height = 48;
  SurfaceRenderSettings settings;
  settings.samplesPerPixel = 1;
  return renderSurfaceRadiance(scene, camera, solution, settings);
}

bool samePixels(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height &&
         std::equal(a.pixels.begin(), a.pixels.end(), b.pixels.begin());
}

SolverSettings someSettings() {
  SolverSettings s;
  s.values["patches"] = int64_t(400);
  return s;
}

PatchRadiositySettings patchSettings() {
  PatchRadiositySettings s;
  s.targetPatches = 400;
  s.formFactorRays = 64;
  s.lightGroups = true;
  return s;
}

TEST(SolutionFile, PatchRoundTripRendersBitForBitWithItsGroups) {
  const Scene scene = boxWithSpot();
  const PatchModel model(scene, patchSettings());
  PatchRadiosity solved = model.solve(scene.lights);
  ASSERT_GT(solved.stats().refinedSplits, 0u);  // the file must rebuild a refined quadtree
  const std::vector<Color> scales = {Color(0.5f, 0.6f, 0.7f), Color(2.0f)};
  solved.setGroupScales(scales);
  const fs::path file = tempFile("patch.rad");
  solved.save(file.string(), someSettings());

  const SolutionFileInfo info = readSolutionFileInfo(file.string());
  EXPECT_EQ(info.method, "patch");
  EXPECT_EQ(std::get<int64_t>(info.settings.values.at("patches")), 400);
  // Another model of the same scene and settings: nothing shared with the first but the input.
  PatchRadiosity loaded = PatchModel(scene, patchSettings()).load(file.string(), scene.lights);
  ASSERT_EQ(loaded.elementCount(), solved.elementCount());
  ASSERT_EQ(loaded.lightGroups().size(), 2u);
  EXPECT_EQ(loaded.groupScales()[0], scales[0]);
  EXPECT_TRUE(samePixels(picture(scene, loaded), picture(scene, solved)));
  // Rescaled after loading, as the solution it was would be.
  loaded.setGroupScales(std::vector<Color>(2, Color(1.0f)));
  solved.setGroupScales(std::vector<Color>(2, Color(1.0f)));
  EXPECT_EQ(largestRadiosityDifference(loaded, solved), 0.0);
  EXPECT_TRUE(samePixels(picture(scene, loaded), picture(scene, solved)));
}

TEST(SolutionFile, VoxelRoundTripRendersBitForBit) {
  const Scene scene = boxWithSpot();
  VoxelRadiositySettings settings;
  settings.targetVoxels = 4000;
  settings.sphereRadius = 6;
  settings.iterations = 3;
  settings.keepDirectLight = true;
  const VoxelModel model(scene, settings);
  const VoxelRadiosity solved = model.solve(scene.lights);
  const fs::path file = tempFile("voxel.rad");
  solved.save(file.string(), {});
  const VoxelRadiosity loaded = VoxelModel(scene, settings).load(file.string(), scene.lights);
  EXPECT_TRUE(loaded.hasIndirectIrradiance());
  EXPECT_EQ(largestRadiosityDifference(loaded, solved), 0.0);
  EXPECT_TRUE(samePixels(picture(scene, loaded), picture(scene, solved)));
}

// The message of the InputError that loading `file` throws ("" if none).
std::string refusal(const fs::path& file, const PatchModel& model, std::span<const Light> lights) {
  try {
    model.load(file.string(), lights);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SolutionFile, CutCorruptOldForeignAndOtherFilesAreRefused) {
  const Scene scene = boxWithSpot();
  PatchRadiositySettings settings = patchSettings();
  settings.lightGroups = false;
  const PatchModel model(scene, settings);
  const fs::path good = tempFile("good.rad");
  model.solve(scene.lights).save(good.string(), someSettings());
  const std::string bytes = bytesOf(good);
  ASSERT_EQ(refusal(good, model, scene.lights), "");

  auto variant = [&](const std::string& name, const std::string& content) {
    const fs::path path = tempFile(name);
    writeBytes(path, content);
    return refusal(path, model, scene.lights);
  };
  EXPECT_NE(variant("cut.rad", bytes.substr(0, bytes.size() / 2)).find("corrupt"),
            std::string::npos);
  std::string flipped = bytes;
  flipped[bytes.size() / 2] ^= 0x20;
  EXPECT_NE(variant("flipped.rad", flipped).find("checksum"), std::string::npos);
  std::string old = bytes;
  old[8] = 0;  // the format version
  EXPECT_NE(variant("old.rad", old).find("version 0"), std::string::npos);
  EXPECT_NE(variant("text.rad", "hello, not a solution\n").find("not a radiosity solution"),
            std::string::npos);
  EXPECT_NE(variant("empty.rad", "").find("empty"), std::string::npos);
  EXPECT_NE(refusal(tempFile("missing.rad"), model, scene.lights).find("no such"),
            std::string::npos);

  // Other lights, another scene, another method.
  std::vector<Light> moved = scene.lights;
  moved[0].position.x += 1.0f;
  EXPECT_NE(refusal(good, model, moved).find("other lights"), std::string::npos);
  const Scene other = loadScene("cornell-spot");
  EXPECT_NE(refusal(good, PatchModel(other, settings), other.lights).find("another scene"),
            std::string::npos);
  VoxelRadiositySettings voxels;
  voxels.targetVoxels = 1000;
  try {
    VoxelModel(scene, voxels).load(good.string(), scene.lights);
    ADD_FAILURE() << "a patch file loaded as a voxel solution";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("a patch solution, not a voxel one"), std::string::npos);
  }
  // Other patch settings: the file's patches are not a refinement of this base mesh.
  PatchRadiositySettings finer = settings;
  finer.targetPatches = 1600;
  EXPECT_NE(refusal(good, PatchModel(scene, finer), scene.lights).find("does not fit"),
            std::string::npos);
}

// `bytes` with the float at `at` set to `value` and the checksum made anew, as a forger would.
std::string forged(std::string bytes, size_t at, float value) {
  std::memcpy(bytes.data() + at, &value, sizeof value);
  const uint64_t sum = checksum(bytes.data(), bytes.size() - 8);
  std::memcpy(bytes.data() + bytes.size() - 8, &sum, 8);
  return bytes;
}

// A radiosity or irradiance that is NaN, infinite or negative is refused as the form-factor
// cache's form factors are (one check), even under a valid checksum: loaded, it would spread
// through every relight and picture. A forged finite positive value still loads (the place is a
// value, not the file's structure).
TEST(SolutionFile, ForgedRadiosityNotFiniteOrNegativeIsRefused) {
  const Scene scene = loadScene("cornell");
  PatchRadiositySettings settings = patchSettings();
  settings.lightGroups = false;
  const PatchModel patch(scene, settings);
  const fs::path patchFile = tempFile("forge_patch.rad");
  const PatchRadiosity solved = patch.solve(scene.lights);
  solved.save(patchFile.string(), someSettings());
  const std::string patchBytes = bytesOf(patchFile);
  // The payload ends: the radiosity (n colours), the direct light's count d and d colours.
  const uint64_t n = solved.elementCount();
  size_t patchAt = 0;
  for (uint64_t d : {uint64_t(0), n}) {
    const size_t count = patchBytes.size() - 8 - 12 * d - 8;
    uint64_t stored = 0;
    std::memcpy(&stored, patchBytes.data() + count, 8);
    if (stored == d) patchAt = count - 12;
  }
  ASSERT_GT(patchAt, 0u);
  VoxelRadiositySettings voxels;
  voxels.targetVoxels = 2000;
  voxels.iterations = 2;
  const VoxelModel voxel(scene, voxels);
  const fs::path voxelFile = tempFile("forge_voxel.rad");
  voxel.solve(scene.lights).save(voxelFile.string(), someSettings());
  const std::string voxelBytes = bytesOf(voxelFile);
  const size_t voxelAt = voxelBytes.size() - 8 - 12;  // its last radiosity, before the checksum

  auto refusedAs = [&](const std::string& bytes, size_t at, float value, bool isPatch) {
    const fs::path path = tempFile("forged.rad");
    writeBytes(path, forged(bytes, at, value));
    try {
      if (isPatch)
        patch.load(path.string(), scene.lights);
      else
        voxel.load(path.string(), scene.lights);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  for (const bool isPatch : {true, false}) {
    const std::string& bytes = isPatch ? patchBytes : voxelBytes;
    const size_t at = isPatch ? patchAt : voxelAt;
    for (const float bad : {std::nanf(""), INFINITY, -1.0f, -1e-30f}) {
      const std::string why = refusedAs(bytes, at, bad, isPatch);
      EXPECT_NE(why.find("radiosity holds a value that is negative or not finite"),
                std::string::npos)
          << (isPatch ? "patch " : "voxel ") << bad << ": " << why;
    }
    EXPECT_EQ(refusedAs(bytes, at, 0.5f, isPatch), "") << (isPatch ? "patch" : "voxel");
  }
}

}  // namespace
}  // namespace rad
