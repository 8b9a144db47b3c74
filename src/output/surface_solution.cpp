// The statistics and exporters every solution shares, through the SurfaceSolution interface.
#include <radiosity/surface_solution.h>

#include "output/gltf_export.h"
#include "output/surface_samples.h"

namespace rad {

namespace {

std::vector<SurfaceElement> elementsOf(const SurfaceSolution& solution) {
  std::vector<SurfaceElement> out(solution.elementCount());
  for (size_t i = 0; i < out.size(); ++i) out[i] = solution.element(i);
  return out;
}

}  // namespace

std::vector<ObjectRadiometry> SurfaceSolution::objectRadiometry() const {
  return meanPerObject(scene(), elementCount(), [&](size_t i) { return element(i); });
}

void SurfaceSolution::exportCsv(const std::string& path) const {
  writeSurfaceElementsCsv(path, scene(), elementsOf(*this));
}

void SurfaceSolution::exportPly(const std::string& path) const {
  writeSurfaceElementsPly(path, elementsOf(*this));
}

void SurfaceSolution::exportGlb(const std::string& path) const {
  writeLitMeshGlb(path, litMesh());
}

}  // namespace rad
