#include "fuzz_support.h"

#include <radiosity/scene_loader.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>

#include "core/binary_io.h"

namespace rad::fuzz {

namespace {

void removeScratch() {
  std::error_code ec;
  std::filesystem::remove_all(scratchDir(), ec);
}

}  // namespace

const std::filesystem::path& scratchDir() {
  static const std::filesystem::path dir = [] {
    const std::filesystem::path d =
        std::filesystem::temp_directory_path() / ("radiosity-fuzz-" + std::to_string(getpid()));
    const std::filesystem::path data = RADIOSITY_TEST_DATA_DIR "/scene";
    std::filesystem::remove_all(d);
    std::filesystem::create_directories(d);
    for (const char* folder : {"small", "ies"})
      std::filesystem::copy(data / folder, d / folder, std::filesystem::copy_options::recursive);
    std::atexit(removeScratch);
    return d;
  }();
  return dir;
}

std::string writeInput(const std::string& relative, std::string_view bytes) {
  const std::filesystem::path path = scratchDir() / relative;
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(bytes.data(), std::streamsize(bytes.size()));
  return path.string();
}

void fixChecksum(std::string& bytes) {
  if (bytes.size() < 8) return;
  const uint64_t sum = checksum(bytes.data(), bytes.size() - 8);
  std::memcpy(bytes.data() + bytes.size() - 8, &sum, 8);
}

const Scene& seedScene() {
  static const Scene scene = loadScene("cornell");
  return scene;
}

PatchRadiositySettings seedPatchSettings(const std::filesystem::path& cacheDir) {
  PatchRadiositySettings s;
  s.targetPatches = 60;
  s.formFactorRays = 64;
  s.lightSamples = 4;
  s.refineLevels = 0;
  s.cacheDir = cacheDir.string();
  return s;
}

VoxelRadiositySettings seedVoxelSettings() {
  VoxelRadiositySettings s;
  s.targetVoxels = 2000;
  s.sphereRadius = 4;
  s.iterations = 2;
  s.directSamples = 4;
  return s;
}

}  // namespace rad::fuzz
