#pragma once
// Per-element results of a radiosity method (a patch or a voxel side) and the files they go to:
// CSV (one row per element, the columns of docs/ARCHITECTURE.md) and a binary PLY point cloud.

#include <radiosity/object_radiometry.h>
#include <radiosity/scene.h>

#include <functional>
#include <span>
#include <string>
#include <vector>

namespace rad {

struct SurfaceSample {
  uint32_t object = 0;
  float area = 0.0f;
  Vec3 position{0.0f};
  Vec3 normal{0.0f};
  Color emitted{0.0f};     ///< E = pi Ke, radiosity emitted
  Color rho{0.0f};
  Color irradiance{0.0f};  ///< H
  Color radiosity{0.0f};   ///< B = E + rho H
  bool backSide = false;   ///< the back of a two-sided face
};

/// Area-weighted mean irradiance and radiosity of each scene object over its elements' front
/// sides (the `objects` table of the stats file).
std::vector<ObjectRadiometry> meanPerObject(const Scene& scene, std::span<const SurfaceSample> samples);
/// The same over `count` samples made one at a time by `sampleAt(i)`: a solution of millions of
/// elements need not hold them all at once (84 bytes each).
std::vector<ObjectRadiometry> meanPerObject(const Scene& scene, size_t count,
                                            const std::function<SurfaceSample(size_t)>& sampleAt);

/// Writes `id,object,area,cx,cy,cz,nx,ny,nz,E_r,...,B_b` rows; object names from `scene`.
void writeSurfaceSamplesCsv(const std::string& path, const Scene& scene,
                            std::span<const SurfaceSample> samples);
/// Writes a binary little-endian PLY: x y z nx ny nz (float), red green blue (uchar: the sRGB
/// tone-mapped radiance B / pi), radiosity_r/g/b (float).
void writeSurfaceSamplesPly(const std::string& path, std::span<const SurfaceSample> samples);

}  // namespace rad
