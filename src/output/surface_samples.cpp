#include <fmt/format.h>
#include <radiosity/atomic_file.h>
#include <radiosity/image.h>
#include <radiosity/surface_samples.h>

#include <cstring>
#include <glm/gtc/constants.hpp>

#include "output/csv_field.h"

namespace rad {

namespace {

template <typename T>
void append(std::string& out, const T& value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

}  // namespace

std::vector<ObjectRadiometry> meanPerObject(const Scene& scene,
                                            std::span<const SurfaceElement> samples) {
  return meanPerObject(scene, samples.size(), [&](size_t i) { return samples[i]; });
}

std::vector<ObjectRadiometry> meanPerObject(const Scene& scene, size_t count,
                                            const std::function<SurfaceElement(size_t)>& sampleAt) {
  std::vector<ObjectRadiometry> objects(scene.objects.size());
  std::vector<Vec3d> h(objects.size(), Vec3d(0.0)), b(objects.size(), Vec3d(0.0));
  for (size_t i = 0; i < count; ++i) {
    const SurfaceElement s = sampleAt(i);
    if (s.backSide) continue;
    objects[s.object].area += s.area;
    h[s.object] += double(s.area) * Vec3d(s.irradiance);
    b[s.object] += double(s.area) * Vec3d(s.radiosity);
  }
  for (size_t o = 0; o < objects.size(); ++o) {
    objects[o].name = scene.objects[o].name;
    if (objects[o].area <= 0.0) continue;
    objects[o].meanIrradiance = Color(h[o] / objects[o].area);
    objects[o].meanRadiosity = Color(b[o] / objects[o].area);
  }
  return objects;
}

std::string objectRadiometryCsv(std::span<const ObjectRadiometry> objects) {
  std::string text = "object,area,H_r,H_g,H_b,B_r,B_g,B_b\n";
  for (const ObjectRadiometry& o : objects)
    text += fmt::format("{},{:g},{:g},{:g},{:g},{:g},{:g},{:g}\n", csvField(o.name), o.area,
                        o.meanIrradiance.r, o.meanIrradiance.g, o.meanIrradiance.b,
                        o.meanRadiosity.r, o.meanRadiosity.g, o.meanRadiosity.b);
  return text;
}

void writeSurfaceElementsCsv(const std::string& path, const Scene& scene,
                             std::span<const SurfaceElement> samples) {
  std::string text =
      "id,object,area,cx,cy,cz,nx,ny,nz,E_r,E_g,E_b,rho_r,rho_g,rho_b,H_r,H_g,H_b,B_r,B_g,B_b\n";
  for (size_t i = 0; i < samples.size(); ++i) {
    const SurfaceElement& s = samples[i];
    const std::string object = s.object < scene.objects.size() ? scene.objects[s.object].name : "";
    text += fmt::format(
        "{},{},{:g},{:g},{:g},{:g},{:g},{:g},{:g},{:g},{:g},{:g},{:g},{:g},{:g},{:g},"
        "{:g},{:g},{:g},{:g},{:g}\n",
        i, csvField(object), s.area, s.position.x, s.position.y, s.position.z, s.normal.x,
        s.normal.y, s.normal.z, s.emitted.r, s.emitted.g, s.emitted.b, s.rho.r, s.rho.g, s.rho.b,
        s.irradiance.r, s.irradiance.g, s.irradiance.b, s.radiosity.r, s.radiosity.g,
        s.radiosity.b);
  }
  writeTextAtomically(path, text);
}

void writeSurfaceElementsPly(const std::string& path, std::span<const SurfaceElement> samples,
                             float exposureEV) {
  std::string out = fmt::format(
      "ply\nformat binary_little_endian 1.0\ncomment radiosity: one vertex per surface element\n"
      "element vertex {}\nproperty float x\nproperty float y\nproperty float z\n"
      "property float nx\nproperty float ny\nproperty float nz\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\n"
      "property float radiosity_r\nproperty float radiosity_g\nproperty float radiosity_b\n"
      "comment colour: sRGB of radiance B / pi x 2^{} (exposure {} EV)\nend_header\n",
      samples.size(), exposureEV, exposureEV);
  for (const SurfaceElement& s : samples) {
    for (float v : {s.position.x, s.position.y, s.position.z, s.normal.x, s.normal.y, s.normal.z})
      append(out, v);
    for (uint8_t c : toneMapPixel(s.radiosity / glm::pi<float>(), exposureEV)) append(out, c);
    for (float v : {s.radiosity.r, s.radiosity.g, s.radiosity.b}) append(out, v);
  }
  writeTextAtomically(path, out);
}

}  // namespace rad
