#pragma once
// What the fuzz targets share. The loaders read files, so each input is written into a scratch
// folder of this process, beside copies of the test data that seeds refer to by relative path.
// A target accepts success or an InputError: any other exception escapes to libFuzzer, which
// reports it as a crash, as it does a sanitizer report, a signal or a timeout.

#include <radiosity/error.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/voxel_radiosity.h>

#include <filesystem>
#include <string>
#include <string_view>

namespace rad::fuzz {

/// /tmp/radiosity-fuzz-<pid>/, holding copies of tests/data/scene/small and .../ies as small/
/// and ies/; removed when the process exits.
const std::filesystem::path& scratchDir();

/// Writes `bytes` to scratchDir() / relative and returns its path.
std::string writeInput(const std::string& relative, std::string_view bytes);

/// Runs `load`: returning, or throwing InputError, is a clean answer to a bad file.
template <typename Load>
void acceptingInputErrors(Load&& load) {
  try {
    load();
  } catch (const InputError&) {
  }
}

/// The binary formats end in a checksum of the rest, which a mutated input almost never
/// matches: recomputed here, so that what lies behind it gets fuzzed.
void fixChecksum(std::string& bytes);

/// The Cornell box and the settings that the seed solutions and caches are made with
/// (seed_corpora.cpp); the fuzz targets load mutated files into models of the same.
const Scene& seedScene();
PatchRadiositySettings seedPatchSettings(const std::filesystem::path& cacheDir);
VoxelRadiositySettings seedVoxelSettings();

}  // namespace rad::fuzz
