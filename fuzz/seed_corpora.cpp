// Writes the seed corpus of every fuzz target into OUT/<target>/: the test data's files for the
// text formats, and for the binary ones a form-factor cache and solution files made by solving
// the Cornell box with the settings the fuzz targets load them with (fuzz_support.h).
//   usage: fuzz_seed_corpora OUT
#include <radiosity/patch_radiosity.h>
#include <radiosity/scene_loader.h>
#include <radiosity/voxel_radiosity.h>

#include <fstream>
#include <iostream>
#include <sstream>

#include "fuzz_support.h"

namespace fs = std::filesystem;

namespace {

const fs::path kData = RADIOSITY_TEST_DATA_DIR "/scene";

std::string contents(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void write(const fs::path& file, const std::string& bytes) {
  fs::create_directories(file.parent_path());
  std::ofstream(file, std::ios::binary) << bytes;
}

// obj_fuzzer's input: the OBJ naming fuzz.mtl, then "%%MTL" and the library.
void objSeeds(const fs::path& out) {
  for (const char* name : {"small/small", "cornell/cornell_box"}) {
    std::string obj = contents(kData / (std::string(name) + ".obj"));
    const std::string mtl = contents(kData / (std::string(name) + ".mtl"));
    const std::string library = fs::path(name).filename().string() + ".mtl";
    if (const size_t at = obj.find(library); at != std::string::npos)
      obj.replace(at, library.size(), "fuzz.mtl");
    write(out / "obj" / fs::path(name).filename(), obj + "\n%%MTL\n" + mtl);
  }
}

void copySeeds(const fs::path& out, const std::string& target,
               std::initializer_list<const char*> files) {
  for (const char* f : files) write(out / target / fs::path(f).filename(), contents(kData / f));
}

// Master form-factor rows (the Cornell box, and the spot-lit box refined), a whole table (the
// exact estimator's), and the solution files of both methods.
void binarySeeds(const fs::path& out) {
  const fs::path cache = out / "form_factor_cache";
  const rad::Scene& cornell = rad::fuzz::seedScene();
  const rad::PatchModel patch(cornell, rad::fuzz::seedPatchSettings(cache));
  patch.solve(cornell.lights).save((out / "solution_file" / "patch.rad").string(), {});
  const rad::Scene spot = rad::loadScene("cornell-spot");
  rad::PatchRadiositySettings refined = rad::fuzz::seedPatchSettings(cache);
  refined.refineLevels = 1;
  rad::PatchModel(spot, refined).solve(spot.lights);
  rad::PatchRadiositySettings exact = rad::fuzz::seedPatchSettings(cache);
  exact.estimator = rad::PatchFormFactorEstimator::Exact;  // whole tables, not master rows
  exact.formFactorRays = 4;
  rad::PatchModel(cornell, exact).solve(cornell.lights);
  const rad::VoxelModel voxel(cornell, rad::fuzz::seedVoxelSettings());
  voxel.solve(cornell.lights).save((out / "solution_file" / "voxel.rad").string(), {});
}

// Bodies of the viewer's POST /api/lights (cornell-spot: light 0 in group "light0"), as the
// page and the API's documentation send them.
void lightsBodySeeds(const fs::path& out) {
  const char* bodies[] = {
      R"({"lights": [{"id": 0, "position": [278, 540, 280], "direction": [0.4, -1, 0]}]})",
      R"({"lights": [{"id": 0, "intensity": [1e5, 8e4, 6e4]}]})",
      R"({"groups": {"light0": 0.5}})",
      R"({"groups": {"light0": [1, 0.5, 0.25]}})",
      (R"({"lights": [{"id": 0, "position": [1, 2, 3], "direction": [0, -1, 0], )"
       R"("intensity": 2e5}], "groups": {"light0": 0}})"),
      R"({"lights": []})",
  };
  int k = 0;
  for (const char* body : bodies)
    write(out / "lights_body" / ("body" + std::to_string(k++) + ".json"), body);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: fuzz_seed_corpora OUT\n";
    return 2;
  }
  const fs::path out = argv[1];
  fs::remove_all(out);
  fs::create_directories(out / "solution_file");
  objSeeds(out);
  copySeeds(out, "gltf", {"small/small.gltf", "small/missing_buffer.gltf", "small/broken.gltf"});
  copySeeds(out, "glb", {"small/small.glb", "small/truncated.glb"});
  copySeeds(out, "scene_json", {"small/scene.json"});
  copySeeds(out, "ies", {"ies/photompy_tilt_include_v19.ies", "ies/photompy_type_b_symmetric.ies"});
  lightsBodySeeds(out);
  binarySeeds(out);
  return 0;
}
