#pragma once
// The per-element results of a radiosity method (SurfaceElement: a patch or a voxel side) as
// per-object means and the files they go to: CSV (one row per element, the columns of
// docs/ARCHITECTURE.md) and a binary PLY point cloud.

#include <radiosity/object_radiometry.h>
#include <radiosity/scene.h>
#include <radiosity/surface_solution.h>

#include <functional>
#include <span>
#include <string>
#include <vector>

namespace rad {

/// Area-weighted mean irradiance and radiosity of each scene object over its elements' front
/// sides (the `objects` table of the stats file).
std::vector<ObjectRadiometry> meanPerObject(const Scene& scene,
                                            std::span<const SurfaceElement> samples);
/// The same over `count` samples made one at a time by `sampleAt(i)`: a solution of millions of
/// elements need not hold them all at once (84 bytes each).
std::vector<ObjectRadiometry> meanPerObject(const Scene& scene, size_t count,
                                            const std::function<SurfaceElement(size_t)>& sampleAt);

/// Writes `id,object,area,cx,cy,cz,nx,ny,nz,E_r,...,B_b` rows; object names from `scene`.
/// The per-object means as CSV: object,area,H_r,H_g,H_b,B_r,B_g,B_b (a header line first).
std::string objectRadiometryCsv(std::span<const ObjectRadiometry> objects);

void writeSurfaceElementsCsv(const std::string& path, const Scene& scene,
                             std::span<const SurfaceElement> samples);
/// Writes a binary little-endian PLY: x y z nx ny nz (float), red green blue (uchar: the sRGB
/// tone-mapped radiance B / pi at `exposureEV`), radiosity_r/g/b (float).
void writeSurfaceElementsPly(const std::string& path, std::span<const SurfaceElement> samples,
                             float exposureEV = 0.0f);

}  // namespace rad
