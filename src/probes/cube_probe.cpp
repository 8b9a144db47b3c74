// The cube view of a probe and the three ways from it to a vertex's irradiance.
#include "probes/cube_probe.h"

#include <radiosity/error.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>

#include "core/rng.h"

namespace rad {

namespace {

// Face f looks along axis f / 2, positive for even f; its texel coordinates (u, v) run along the
// next two axes, so that a face's point is sign * e_axis + u e_b + v e_c.
struct FaceAxes {
  int axis, b, c;
  float sign;
};
FaceAxes axesOf(int face) {
  const int axis = face / 2;
  return {axis, (axis + 1) % 3, (axis + 2) % 3, face % 2 == 0 ? 1.0f : -1.0f};
}

// The unit direction through face `face`'s point at texel coordinates (i, j) (continuous: the
// texel's centre is i + 0.5) of a face `n` texels wide.
Vec3 faceDirection(int face, float i, float j, int n) {
  const FaceAxes a = axesOf(face);
  Vec3 d(0.0f);
  d[a.axis] = a.sign;
  d[a.b] = -1.0f + i * 2.0f / float(n);
  d[a.c] = -1.0f + j * 2.0f / float(n);
  return glm::normalize(d);
}

// The solid angle of [0, x] x [0, y] on the plane at distance 1 seen from the origin's foot:
// atan(x y / sqrt(x^2 + y^2 + 1)), whose four corners give a texel's.
double cornerSolidAngle(double x, double y) {
  return std::atan2(x * y, std::sqrt(x * x + y * y + 1.0));
}

// The real spherical harmonics up to order 2 at a unit direction.
std::array<double, 9> harmonicsAt(const Vec3& d) {
  const double x = d.x, y = d.y, z = d.z;
  return {0.282095,
          0.488603 * y,
          0.488603 * z,
          0.488603 * x,
          1.092548 * x * y,
          1.092548 * y * z,
          0.315392 * (3.0 * z * z - 1.0),
          1.092548 * x * z,
          0.546274 * (x * x - y * y)};
}

// A point of the cube's surface reached by walking from face `face`'s point (u, v) across its
// edges onto the faces around it (the face unfolded), as a direction; walks of more than a face
// beyond an edge stop at the far edge.
Vec3 foldedDirection(int face, float u, float v) {
  const FaceAxes a = axesOf(face);
  Vec3 p(0.0f);
  p[a.axis] = a.sign;
  auto fold = [&](float& t, int along) {
    if (std::abs(t) <= 1.0f) {
      p[along] = t;
      return;
    }
    const float beyond = std::min(std::abs(t) - 1.0f, 2.0f);
    p[along] = t > 0.0f ? 1.0f : -1.0f;
    p[a.axis] = a.sign * (1.0f - beyond);
  };
  fold(u, a.b);
  if (std::abs(u) > 1.0f && std::abs(v) > 1.0f)
    v = std::clamp(v, -1.0f, 1.0f);  // a corner: one fold
  fold(v, a.c);
  return glm::normalize(p);
}

}  // namespace

CubeProbe::CubeProbe(int resolution, int samples)
    : resolution_(resolution),
      samples_(samples),
      texels_(size_t(6) * resolution * resolution, Color(0.0f)) {
  if (resolution < 1 || resolution > 1024)
    throw InputError("probe", "resolution must be 1 to 1024 texels a face");
  if (samples < 1 || samples > 16) throw InputError("probe", "samples must be 1 to 16 a side");
  const double step = 2.0 / resolution;
  solidAngle_.resize(size_t(resolution) * resolution);
  for (int j = 0; j < resolution; ++j)
    for (int i = 0; i < resolution; ++i) {
      const double u0 = -1.0 + i * step, v0 = -1.0 + j * step;
      solidAngle_[size_t(j) * resolution + i] =
          cornerSolidAngle(u0 + step, v0 + step) - cornerSolidAngle(u0, v0 + step) -
          cornerSolidAngle(u0 + step, v0) + cornerSolidAngle(u0, v0);
    }
  for (int face = 0; face < 6; ++face)
    for (int j = 0; j < resolution; ++j)
      for (int i = 0; i < resolution; ++i) {
        directions_.push_back(faceDirection(face, float(i) + 0.5f, float(j) + 0.5f, resolution));
        texelSolidAngle_.push_back(float(solidAngle(i, j)));
      }
  // The published pattern: over a square twice a face's size around where the normal meets the
  // cube, four texels at random on every ring (square) around its centre, drawn once.
  Rng rng(0x70726f6265ull, uint64_t(resolution));
  ring_.push_back({0.0f, 0.0f});
  for (int k = 1; k <= resolution; ++k)
    for (int s = 0; s < 4; ++s) {
      const int along = int(rng.uniform() * float(2 * k)) - k;  // -k .. k-1 along a side
      const int side = int(rng.uniform() * 4.0f) % 4;           // which of the ring's four sides
      const std::array<int, 2> offset = side == 0   ? std::array<int, 2>{k, along}
                                        : side == 1 ? std::array<int, 2>{-k, -along}
                                        : side == 2 ? std::array<int, 2>{-along, k}
                                                    : std::array<int, 2>{along, -k};
      ring_.push_back({float(offset[0]), float(offset[1])});
    }
}

size_t CubeProbe::texelOf(const Vec3& d) const {
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(d[k]) > std::abs(d[axis])) axis = k;
  const int face = 2 * axis + (d[axis] < 0.0f ? 1 : 0);
  const FaceAxes a = axesOf(face);
  const float scale = 1.0f / std::abs(d[axis]);
  auto texelAt = [&](float t) {
    return std::clamp(int((t * scale + 1.0f) * 0.5f * float(resolution_)), 0, resolution_ - 1);
  };
  return index(face, texelAt(d[a.b]), texelAt(d[a.c]));
}

void CubeProbe::capture(const RayCaster& caster, const SurfaceRadiance& radiance,
                        const Vec3& centre) {
  centre_ = centre;
  const int n = resolution_;
  tbb::parallel_for(tbb::blocked_range<int>(0, 6 * n), [&](const auto& rows) {
    for (int row = rows.begin(); row != rows.end(); ++row) {
      const int face = row / n, j = row % n;
      for (int i = 0; i < n; ++i) {
        Color sum(0.0f);
        for (int sj = 0; sj < samples_; ++sj)
          for (int si = 0; si < samples_; ++si) {
            const Ray ray{centre,
                          faceDirection(face, float(i) + (float(si) + 0.5f) / float(samples_),
                                        float(j) + (float(sj) + 0.5f) / float(samples_), n)};
            const Hit hit = caster.intersect(ray);
            if (hit.valid())
              sum += radiance.radiance({centre + hit.distance * ray.direction, hit.geometricNormal,
                                        hit.triangle, hit.frontFace, hit.barycentric});
          }
        texel(face, i, j) = sum / float(samples_ * samples_);
      }
    }
  });
  project();
}

void CubeProbe::project() {
  harmonics_.fill(Vec3d(0.0));
  for (int face = 0; face < 6; ++face)
    for (int j = 0; j < resolution_; ++j)
      for (int i = 0; i < resolution_; ++i) {
        const std::array<double, 9> y = harmonicsAt(direction(face, i, j));
        const Vec3d l = Vec3d(texels_[index(face, i, j)]) * solidAngle(i, j);
        for (size_t k = 0; k < 9; ++k) harmonics_[k] += y[k] * l;
      }
}

Color CubeProbe::exactIrradiance(const Vec3& n) const {
  Color sum(0.0f);
  for (size_t t = 0; t < texels_.size(); ++t) {
    const float cosine = glm::dot(n, directions_[t]);
    if (cosine > 0.0f) sum += texels_[t] * (cosine * texelSolidAngle_[t]);
  }
  return sum;
}

Color CubeProbe::harmonicIrradiance(const Vec3& n) const {
  // The cosine lobe's convolution weights by order: pi, 2 pi / 3, pi / 4.
  constexpr double pi = glm::pi<double>();
  constexpr std::array<double, 9> lobe = {pi,     2 * pi / 3, 2 * pi / 3, 2 * pi / 3, pi / 4,
                                          pi / 4, pi / 4,     pi / 4,     pi / 4};
  const std::array<double, 9> y = harmonicsAt(n);
  Vec3d e(0.0);
  for (size_t k = 0; k < 9; ++k) e += lobe[k] * y[k] * harmonics_[k];
  return Color(glm::max(e, Vec3d(0.0)));
}

Color CubeProbe::patternIrradiance(const Vec3& n) const {
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(n[k]) > std::abs(n[axis])) axis = k;
  const int face = 2 * axis + (n[axis] < 0.0f ? 1 : 0);
  const FaceAxes a = axesOf(face);
  const float u0 = n[a.b] / std::abs(n[axis]), v0 = n[a.c] / std::abs(n[axis]);
  const float step = 2.0f / float(resolution_);
  Vec3d sum(0.0);
  for (const std::array<float, 2>& offset : ring_)
    sum += Vec3d(
        texels_[texelOf(foldedDirection(face, u0 + offset[0] * step, v0 + offset[1] * step))]);
  return Color(glm::pi<double>() * sum / double(ring_.size()));
}

Color CubeProbe::irradiance(const Vec3& n, ProbeIrradiance way) const {
  switch (way) {
    case ProbeIrradiance::Exact:
      return exactIrradiance(n);
    case ProbeIrradiance::Harmonic:
      return harmonicIrradiance(n);
    case ProbeIrradiance::Pattern:
      break;
  }
  return patternIrradiance(n);
}

}  // namespace rad
