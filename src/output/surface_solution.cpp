// The statistics and exporters every solution shares, through the SurfaceSolution interface.
#include <fmt/format.h>
#include <radiosity/gltf_export.h>
#include <radiosity/surface_samples.h>
#include <radiosity/surface_solution.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "output/lightmap_atlas.h"

namespace rad {

namespace {

std::vector<SurfaceElement> elementsOf(const SurfaceSolution& solution) {
  std::vector<SurfaceElement> out(solution.elementCount());
  for (size_t i = 0; i < out.size(); ++i) out[i] = solution.element(i);
  return out;
}

}  // namespace

std::vector<ObjectRadiometry> SurfaceSolution::objectRadiometry() const {
  std::vector<ObjectRadiometry> objects =
      meanPerObject(scene(), elementCount(), [&](size_t i) { return element(i); });
  const size_t groups = lightGroups().size();
  if (groups == 0) return objects;
  std::vector<std::vector<double>> power(objects.size(), std::vector<double>(groups, 0.0));
  for (size_t i = 0; i < elementCount(); ++i) {
    const SurfaceElement e = element(i);
    if (e.backSide) continue;
    for (size_t g = 0; g < groups; ++g)
      power[e.object][g] += double(e.area) * luminance(groupRadiosity(g, i));
  }
  for (size_t o = 0; o < objects.size(); ++o) {
    double total = 0.0;
    for (double p : power[o]) total += p;
    objects[o].groupShares.assign(groups, 0.0);
    if (total > 0.0)
      for (size_t g = 0; g < groups; ++g) objects[o].groupShares[g] = power[o][g] / total;
  }
  return objects;
}

void SurfaceSolution::setGroupScales(std::span<const Color> scales) {
  if (!scales.empty())
    throw std::invalid_argument("this solution's light groups were not solved apart");
}

Color SurfaceSolution::groupRadiosity(size_t /*group*/, size_t /*index*/) const {
  throw std::invalid_argument("this solution's light groups were not solved apart");
}

void SurfaceSolution::save(const std::string& /*path*/, const SolverSettings& /*settings*/) const {
  throw std::logic_error("this method's solutions are not saved to files");
}

void SurfaceSolution::exportCsv(const std::string& path) const {
  writeSurfaceElementsCsv(path, scene(), elementsOf(*this));
}

void SurfaceSolution::exportPly(const std::string& path, float exposureEV) const {
  writeSurfaceElementsPly(path, elementsOf(*this), exposureEV);
}

void SurfaceSolution::exportGlb(const std::string& path, float exposureEV) const {
  writeLitMeshGlb(path, litMesh(), exposureEV);
}

void SurfaceSolution::exportLightmappedGlb(const std::string& path, int size,
                                           float exposureEV) const {
  const LightmapAtlas atlas = packLightmapAtlas(scene(), size);
  LightmapImages images = shadeLightmapAtlas(atlas, *this);
  const std::string exrPath = lightmapIrradiancePath(path);
  writeImage(exrPath, images.irradiance, {0.0f, ExrPixelType::Float});
  GlbLightmap lightmap{std::move(images.radiance),
                       std::filesystem::path(exrPath).filename().string(), atlas.texelsPerUnit};
  try {
    writeLitMeshGlb(path, lightmappedMesh(scene(), atlas), exposureEV, &lightmap);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(exrPath, ignored);  // no half of the pair left behind
    throw;
  }
}

std::string lightmapIrradiancePath(const std::string& glbPath) {
  return std::filesystem::path(glbPath).replace_extension(".lightmap.exr").string();
}

double largestRadiosityDifference(const SurfaceSolution& solution,
                                  const SurfaceSolution& reference) {
  const size_t n = reference.elementCount();
  if (solution.elementCount() != n)
    throw std::invalid_argument(fmt::format("solutions of {} and {} elements cannot be compared",
                                            solution.elementCount(), n));
  double mean = 0.0, area = 0.0, largest = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const SurfaceElement e = reference.element(i);
    mean += e.area * (double(e.radiosity.r) + e.radiosity.g + e.radiosity.b) / 3.0;
    area += e.area;
    largest = std::max(largest,
                       double(maxComponent(glm::abs(solution.element(i).radiosity - e.radiosity))));
  }
  return mean > 0.0 ? largest * area / mean : largest;
}

}  // namespace rad
