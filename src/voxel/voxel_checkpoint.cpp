#include "voxel/voxel_checkpoint.h"

#include <fmt/format.h>

#include "core/checksummed_file.h"
#include "scene/scene_hash.h"

namespace rad {

namespace {

constexpr char kMagic[8] = {'R', 'A', 'D', 'V', 'C', 'K', 'P', 'T'};
constexpr uint32_t kVersion = 2;

}  // namespace

std::filesystem::path voxelCheckpointFile(const Scene& scene, const VoxelGrid& grid,
                                          std::span<const Light> lights,
                                          const VoxelSolverSettings& s) {
  if (s.checkpointDir.empty()) return {};
  Hasher h;
  h.value(kVersion);
  hashGeometry(h, scene);
  hashMaterials(h, scene);
  hashLights(h, lights);
  h.value(grid.voxelSize);
  h.value(grid.dims);
  h.value(uint64_t(grid.entryCount()));
  for (const int v : {s.sphereRadius, s.laterSphereRadius, s.iterations, s.directSamples})
    h.value(v);
  h.value(s.tolerance);
  for (const bool b : {s.estimateTail, s.directFirstShot, s.normalize, s.jitterLines,
                       s.keepsDirect(), s.tangentCorrection})
    h.value(uint8_t(b));
  h.value(uint64_t(s.emissionScales.size()));
  for (const Color& c : s.emissionScales) h.value(c);
  h.value(s.seed);
  return std::filesystem::path(s.checkpointDir) / ("voxel-" + h.key().hex() + ".checkpoint");
}

std::string saveVoxelCheckpoint(const std::filesystem::path& file, const VoxelCheckpoint& c) {
  std::string out(kMagic, 8);
  put(out, kVersion);
  put(out, int32_t(c.iterationsDone));
  put(out, uint64_t(c.irradiance.size()));
  putArray<Color>(out, c.irradiance);
  putArray<Color>(out, c.bounce);
  put(out, uint64_t(c.direct.size()));
  putArray<Color>(out, c.direct);
  put(out, uint64_t(c.bouncePower.size()));
  putArray<Vec3d>(out, c.bouncePower);
  putArray<double>(out, c.residuals);
  putArray<double>(out, c.iterationSeconds);
  put(out, c.totalPower);
  put(out, c.sourcePower);
  put(out, c.cellVisits);
  put(out, c.shadowRays);
  put(out, c.directSeconds);
  return saveChecksummed(file, out, "voxel checkpoint");
}

std::optional<VoxelCheckpoint> loadVoxelCheckpoint(const std::filesystem::path& file, size_t sides,
                                                   std::string& warning) {
  return readCheckpoint<VoxelCheckpoint>(
      file, kMagic, kVersion, "voxel checkpoint", "solving from the start", warning,
      [&](ByteReader& in, VoxelCheckpoint& c) -> std::string {
        c.iterationsDone = in.get<int32_t>();
        if (in.get<uint64_t>() != sides) return "made for another grid";
        c.irradiance = in.array<Color>(sides);
        c.bounce = in.array<Color>(sides);
        c.direct = in.array<Color>(in.get<uint64_t>());
        const uint64_t iterations = in.get<uint64_t>();
        c.bouncePower = in.array<Vec3d>(iterations);
        c.residuals = in.array<double>(iterations);
        c.iterationSeconds = in.array<double>(iterations);
        c.totalPower = in.get<Vec3d>();
        c.sourcePower = in.get<Vec3d>();
        c.cellVisits = in.get<uint64_t>();
        c.shadowRays = in.get<uint64_t>();
        c.directSeconds = in.get<double>();
        const bool consistent =
            in.atEnd() && c.iterationsDone >= 0 && uint64_t(c.iterationsDone) == iterations;
        return consistent ? "" : "inconsistent";
      });
}

}  // namespace rad
