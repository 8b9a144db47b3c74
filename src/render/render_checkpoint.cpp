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
  // (only when set, so that the radiance pictures' checkpoints keep their names)
  if (settings.irradiance) h.text("irradiance");
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
  return readCheckpoint<RenderCheckpoint>(
      file, kMagic, kVersion, "render checkpoint", "rendering from the start", warning,
      [&](ByteReader& in, RenderCheckpoint& c) -> std::string {
        const int32_t w = in.get<int32_t>(), h = in.get<int32_t>();
        if (w != width || h != height || in.get<uint64_t>() != tiles)
          return "made for another picture";
        c.tileDone = in.array<uint8_t>(tiles);
        c.image = Image(width, height);
        c.image.pixels = in.array<Color>(uint64_t(width) * uint64_t(height));
        return in.atEnd() ? "" : "inconsistent";
      });
}

}  // namespace rad
