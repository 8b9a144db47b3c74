#pragma once
// A floor under a light, and the closed forms of what it receives: the tests of direct light
// from point, spot and IES lights.

#include <radiosity/scene_builder.h>

#include <cmath>
#include <glm/gtc/constants.hpp>
#include <optional>

#include "render/test_scenes.h"

namespace rad::test {

/// Solid angle of the rectangle [0, a] x [0, b] of a plane seen from a point at height h above
/// the corner (0, 0): atan(ab / (h sqrt(a^2 + b^2 + h^2))) (the classic corner formula, e.g.
/// Gardner's rectangle solid angle; it follows from integrating cos / d^2 = h / d^3 over the
/// rectangle).
inline double cornerSolidAngle(double a, double b, double h) {
  return std::atan(a * b / (h * std::sqrt(a * a + b * b + h * h)));
}

/// Solid angle of [x0, x1] x [z0, z1] seen from height h above the plane's point (px, pz), by
/// superposition of signed corner rectangles (works with the point outside the rectangle).
inline double rectangleSolidAngle(double px, double pz, double x0, double x1, double z0, double z1,
                                  double h) {
  auto corner = [&](double u, double v) {
    const double s = cornerSolidAngle(std::abs(u), std::abs(v), h);
    return (u < 0) != (v < 0) ? -s : s;
  };
  return corner(x1 - px, z1 - pz) - corner(x0 - px, z1 - pz) - corner(x1 - px, z0 - pz) +
         corner(x0 - px, z0 - pz);
}

/// The square floor [-half, half]^2 at y = 0 facing +y (object "floor", rho 0.5), optionally a
/// square occluder of half-size `occluderHalf` centred above the origin at `occluderHeight`
/// (object "occluder", facing up), and the light.
inline Scene floorUnderLight(float half, const Light& light, float occluderHalf = 0.0f,
                             float occluderHeight = 0.0f) {
  SceneBuilder b("floor");
  const uint32_t m = b.addMaterial({"grey", Color(0.5f), Color(0.0f), false});
  const uint32_t floor = b.addObject("floor");
  addQuadFacing(b, axisSquare(Vec3(0.0f), 1, 2.0f * half), Vec3(0, 1, 0), m, floor);
  if (occluderHalf > 0.0f) {
    const uint32_t occluder = b.addObject("occluder");
    addQuadFacing(b, axisSquare(Vec3(0.0f, occluderHeight, 0.0f), 1, 2.0f * occluderHalf),
                  Vec3(0, 1, 0), m, occluder);
  }
  b.scene().lights.push_back(light);
  return b.build();
}

inline Light pointLight(const Vec3& position, const Color& intensity) {
  Light l;
  l.type = LightType::Point;
  l.position = position;
  l.intensity = intensity;
  return l;
}

/// A spot at `position` aimed straight down.
inline Light downSpot(const Vec3& position, const Color& intensity, float innerDeg,
                      float outerDeg) {
  Light l = pointLight(position, intensity);
  l.type = LightType::Spot;
  l.direction = Vec3(0.0f, -1.0f, 0.0f);
  l.innerAngleDeg = innerDeg;
  l.outerAngleDeg = outerDeg;
  return l;
}

/// The spot profile of docs/ARCHITECTURE.md written out here (not the library's): 1 inside the
/// inner half-angle, 0 outside the outer one, a smoothstep in cos between.
inline double spotFalloff(double cosTheta, double innerDeg, double outerDeg) {
  const double cosOuter = std::cos(outerDeg * glm::pi<double>() / 180.0);
  const double cosInner = std::cos(innerDeg * glm::pi<double>() / 180.0);
  if (cosTheta <= cosOuter) return 0.0;
  if (cosTheta >= cosInner) return 1.0;
  const double t = (cosTheta - cosOuter) / (cosInner - cosOuter);
  return t * t * (3.0 - 2.0 * t);
}

/// The mean over the floor [-half, half]^2 (y = 0, normal +y) of intensity(toward) cos / d^2
/// from a light at `position`, by the composite midpoint rule on an n x n grid in double: the
/// independent numerical integral the spot and IES tests compare with.
template <class IntensityToward>
double meanFloorIrradiance(double half, const Vec3d& position, int n, IntensityToward intensity) {
  double sum = 0.0;
  const double step = 2.0 * half / n;
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k) {
      const Vec3d p(-half + (i + 0.5) * step, 0.0, -half + (k + 0.5) * step);
      const Vec3d d = p - position;
      const double d2 = glm::dot(d, d);
      const Vec3d toward = d / std::sqrt(d2);
      const double cosReceiver = -toward.y;
      if (cosReceiver > 0.0) sum += intensity(toward) * cosReceiver / d2;
    }
  return sum / (double(n) * n);
}

}  // namespace rad::test
