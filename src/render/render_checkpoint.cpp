#include "render/render_checkpoint.h"

#include <fmt/format.h>

#include "core/binary_io.h"
#include "core/checksummed_file.h"
#include "scene/scene_hash.h"

namespace rad {

namespace {

constexpr char kMagic[8] = {'R', 'A', 'D', 'T', 'I', 'L', 'E', 'S'};
constexpr uint32_t kVersion = 1;

}  // namespace

std::filesystem::path renderCheckpointFile(const Scene& scene, const Camera& camera,
                                           const PathTracerSettings& settings) {
  if (settings.checkpointDir.empty()) return {};
  Hasher h;
  h.value(kVersion);
  hashGeometry(h, scene);
  hashMaterials(h, scene);
  hashLights(h, scene.lights);
  for (const Vec3& v : {camera.eye, camera.target, camera.up}) h.value(v);
  h.value(camera.fovDeg);
  for (const int v : {camera.width, camera.height, settings.samplesPerPixel, settings.maxDepth})
    h.value(v);
  h.value(settings.seed);
  return std::filesystem::path(settings.checkpointDir) /
         ("pathtrace-" + h.key().hex() + ".checkpoint");
}

std::string saveRenderCheckpoint(const std::filesystem::path& file, const RenderCheckpoint& c) {
  std::string out(kMagic, 8);
  put(out, kVersion);
  put(out, int32_t(c.image.width));
  put(out, int32_t(c.image.height));
  put(out, uint64_t(c.tileDone.size()));
  putArray<uint8_t>(out, c.tileDone);
  putArray<Color>(out, c.image.pixels);
  return saveChecksummed(file, out, "render checkpoint");
}

std::optional<RenderCheckpoint> loadRenderCheckpoint(const std::filesystem::path& file,
                                                     size_t tiles, int width, int height,
                                                     std::string& warning) {
  const ChecksummedFile f = readChecksummed(file, kMagic, "render checkpoint");
  if (!f.exists) return std::nullopt;
  auto reject = [&](const std::string& why) -> std::optional<RenderCheckpoint> {
    warning = fmt::format("render checkpoint {} not used ({}); rendering from the start",
                          file.string(), why);
    return std::nullopt;
  };
  if (!f.rejected.empty()) return reject(f.rejected);
  const std::string& bytes = f.bytes;
  RenderCheckpoint c;
  try {
    ByteReader in(bytes, 8, bytes.size() - 8);
    if (const uint32_t version = in.get<uint32_t>(); version != kVersion)
      return reject(fmt::format("format version {}, expected {}", version, kVersion));
    const int32_t w = in.get<int32_t>(), h = in.get<int32_t>();
    if (w != width || h != height || in.get<uint64_t>() != tiles)
      return reject("made for another picture");
    c.tileDone = in.array<uint8_t>(tiles);
    c.image = Image(width, height);
    c.image.pixels = in.array<Color>(uint64_t(width) * uint64_t(height));
    if (!in.atEnd()) return reject("inconsistent");
  } catch (const std::out_of_range&) {
    return reject("truncated");
  }
  return c;
}

}  // namespace rad
