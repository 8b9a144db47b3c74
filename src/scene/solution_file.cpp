// The solution files' container: what every method's file starts and ends with.
#include "scene/solution_file.h"

#include <fmt/format.h>
#include <radiosity/atomic_file.h>
#include <radiosity/error.h>

#include <cstring>

#include "scene/scene_hash.h"

namespace rad {

namespace {

constexpr char kMagic[8] = {'R', 'A', 'D', 'S', 'O', 'L', 'N', '\n'};
constexpr uint32_t kVersion = 1;

Key128 keyOf(const Scene& scene, std::span<const Light> lights) {
  Hasher h;
  h.value(kVersion);
  hashGeometry(h, scene);
  hashMaterials(h, scene);
  hashLights(h, lights);
  return h.key();
}

// Settings as name, type index and value.
void putSettings(std::string& out, const SolverSettings& settings) {
  put(out, uint64_t(settings.values.size()));
  for (const auto& [name, value] : settings.values) {
    putText(out, name);
    put(out, uint8_t(value.index()));
    if (const bool* b = std::get_if<bool>(&value)) put(out, uint8_t(*b));
    if (const int64_t* i = std::get_if<int64_t>(&value)) put(out, *i);
    if (const double* d = std::get_if<double>(&value)) put(out, *d);
    if (const std::string* s = std::get_if<std::string>(&value)) putText(out, *s);
  }
}

SolverSettings getSettings(ByteReader& in) {
  SolverSettings settings;
  const uint64_t count = in.get<uint64_t>();
  for (uint64_t k = 0; k < count; ++k) {
    std::string name = in.text();
    switch (in.get<uint8_t>()) {
      case 0:
        settings.values[name] = in.get<uint8_t>() != 0;
        break;
      case 1:
        settings.values[name] = in.get<int64_t>();
        break;
      case 2:
        settings.values[name] = in.get<double>();
        break;
      case 3:
        settings.values[name] = in.text();
        break;
      default:
        throw std::out_of_range("a setting of unknown type");
    }
  }
  return settings;
}

}  // namespace

std::string solutionFileStart(const std::string& method, const Scene& scene,
                              std::span<const Light> lights, const SolverSettings& settings) {
  std::string out(kMagic, 8);
  put(out, kVersion);
  const Key128 key = keyOf(scene, lights);
  put(out, key.high);
  put(out, key.low);
  putText(out, method);
  putSettings(out, settings);
  return out;
}

void writeSolutionFile(const std::string& path, std::string& bytes) {
  put(bytes, checksum(bytes.data(), bytes.size()));
  writeBytesAtomically(path, bytes);
}

SolutionFile::SolutionFile(const std::string& file) : path(file) {
  auto fail = [&](const std::string& why) { throw InputError(path, why); };
  if (!readWholeFile(path, bytes)) fail("no such solution file");
  if (bytes.size() < 8 || std::memcmp(bytes.data(), kMagic, 8) != 0)
    fail(bytes.empty() ? "empty or unreadable" : "not a radiosity solution file");
  if (bytes.size() < 8 + 4 + 16 + 8) fail("truncated");
  size_t at = 8;
  const uint32_t version = get<uint32_t>(bytes, at);
  if (version != kVersion)
    fail(
        fmt::format("solution file format version {}, this radiosity reads version {}: solve "
                    "again to write it anew",
                    version, kVersion));
  if (!checksumMatches(bytes)) fail("checksum mismatch: the file is truncated or corrupt");
  key = {get<uint64_t>(bytes, at), get<uint64_t>(bytes, at)};
  try {
    ByteReader in(bytes, at, bytes.size() - 8);
    info.method = in.text();
    info.settings = getSettings(in);
    payloadBegin = in.position();
  } catch (const std::out_of_range& e) {
    fail(fmt::format("corrupt header ({})", e.what()));
  }
  payloadEnd = bytes.size() - 8;
}

void SolutionFile::checkFor(const std::string& method, const Scene& scene,
                            std::span<const Light> lights) const {
  if (info.method != method)
    throw InputError(path, fmt::format("a {} solution, not a {} one", info.method, method));
  if (!(key == keyOf(scene, lights)))
    throw InputError(path, fmt::format("solved for another scene or other lights than {} has "
                                       "now (its geometry, materials or lights differ): solve "
                                       "it again",
                                       scene.name));
}

std::vector<Color> SolutionFile::radiometry(ByteReader& in, uint64_t count,
                                            const char* what) const {
  std::vector<Color> colors = in.array<Color>(count);
  static_assert(sizeof(Color) == 3 * sizeof(float));
  if (!allFiniteNonNegative({reinterpret_cast<const float*>(colors.data()), 3 * colors.size()}))
    refuse(fmt::format("its {} holds a value that is negative or not finite", what));
  return colors;
}

void SolutionFile::refuse(const std::string& why) const {
  throw InputError(path, fmt::format("does not fit the scene: {}", why));
}

SolutionFileInfo readSolutionFileInfo(const std::string& path) {
  return SolutionFile(path).info;
}

}  // namespace rad
