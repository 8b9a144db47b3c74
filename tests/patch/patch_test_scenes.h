#pragma once
// Scenes for the patch method's tests, built by hand (independent of the loaders), and the
// closed-form view factors of docs/references.md section 1 they are checked against.

#include <radiosity/scene_builder.h>

#include <cmath>
#include <glm/gtc/constants.hpp>
#include <vector>

#include "patch/form_factor_table.h"
#include "patch/patch_mesh.h"
#include "render/test_scenes.h"
#include "voxel/voxel_test_scenes.h"

namespace rad::test {

inline Material grey(float rho) {
  return {"grey", Color(rho), Color(0.0f), false};
}

/// 1(a): a x b rectangles at z = 0 (facing +z, object 0 "a") and z = c (facing -z, object 1).
inline Scene parallelRectangles(float a, float b, float c) {
  SceneBuilder s("parallel");
  const uint32_t m = s.addMaterial(grey(0.5f));
  const uint32_t lo = s.addObject("a"), hi = s.addObject("b");
  addQuadFacing(s, {Vec3(0, 0, 0), Vec3(a, 0, 0), Vec3(a, b, 0), Vec3(0, b, 0)}, Vec3(0, 0, 1), m,
                lo);
  addQuadFacing(s, {Vec3(0, 0, c), Vec3(a, 0, c), Vec3(a, b, c), Vec3(0, b, c)}, Vec3(0, 0, -1), m,
                hi);
  return s.build();
}

/// 1(b): floor w x l (object 0) and wall h x l (object 1) sharing the edge of length l (x axis).
inline Scene perpendicularRectangles(float w, float h, float l) {
  SceneBuilder s("perpendicular");
  const uint32_t m = s.addMaterial(grey(0.5f));
  const uint32_t floor = s.addObject("a"), wall = s.addObject("b");
  addQuadFacing(s, {Vec3(0, 0, 0), Vec3(l, 0, 0), Vec3(l, 0, w), Vec3(0, 0, w)}, Vec3(0, 1, 0), m,
                floor);
  addQuadFacing(s, {Vec3(0, 0, 0), Vec3(l, 0, 0), Vec3(l, h, 0), Vec3(0, h, 0)}, Vec3(0, 0, 1), m,
                wall);
  return s.build();
}

/// 1(c): coaxial discs as regular `sides`-gons of the same area as the discs: radius r1 at z = 0
/// facing +z (object 0), radius r2 at z = a facing -z (object 1).
inline Scene coaxialDiscs(float r1, float r2, float a, int sides) {
  SceneBuilder s("discs");
  const uint32_t m = s.addMaterial(grey(0.5f));
  // Equal area: the n-gon's circumradius R satisfies (n/2) R^2 sin(2 pi/n) = pi r^2.
  const double k =
      std::sqrt(2.0 * glm::pi<double>() / (sides * std::sin(2.0 * glm::pi<double>() / sides)));
  for (int disc = 0; disc < 2; ++disc) {
    const uint32_t object = s.addObject(disc == 0 ? "a" : "b");
    const float r = float(k) * (disc == 0 ? r1 : r2), z = disc == 0 ? 0.0f : a;
    std::vector<uint32_t> ids;
    for (int i = 0; i < sides; ++i) {
      const float phi =
          2.0f * glm::pi<float>() * float(i) / float(sides) * (disc == 0 ? 1.0f : -1.0f);
      ids.push_back(s.addVertex(Vec3(r * std::cos(phi), r * std::sin(phi), z), "disc"));
    }
    s.addPolygon(ids, m, object, "disc");
  }
  return s.build();
}

/// Face-level F from object 0 to object 1: sum over their patches of A_i F_ij / A_0.
inline double objectFormFactor(const PatchMesh& mesh, const FormFactorTable& table) {
  double flux = 0.0, area = 0.0;
  for (uint32_t i = 0; i < mesh.size(); ++i) {
    if (mesh.patches()[i].object != 0) continue;
    area += mesh.patches()[i].area;
    const auto cols = table.columns(i);
    for (size_t k = 0; k < cols.size(); ++k)
      if (mesh.patches()[cols[k]].object == 1)
        flux += double(mesh.patches()[i].area) * table.values(i)[k];
  }
  return flux / area;
}

// Closed forms of docs/references.md 1(a), 1(b), 1(c) (1(d) is in render/test_scenes.h).
inline double parallelRectanglesF(double a, double b, double c) {
  const double X = a / c, Y = b / c, pi = glm::pi<double>();
  return 2.0 / (pi * X * Y) *
         (std::log(std::sqrt((1 + X * X) * (1 + Y * Y) / (1 + X * X + Y * Y))) +
          X * std::sqrt(1 + Y * Y) * std::atan(X / std::sqrt(1 + Y * Y)) +
          Y * std::sqrt(1 + X * X) * std::atan(Y / std::sqrt(1 + X * X)) - X * std::atan(X) -
          Y * std::atan(Y));
}
inline double perpendicularRectanglesF(double w, double h, double l) {
  const double W = w / l, H = h / l, W2 = W * W, H2 = H * H, S = W2 + H2;
  const double L = std::log((1 + W2) * (1 + H2) / (1 + S)) +
                   W2 * std::log(W2 * (1 + S) / ((1 + W2) * S)) +
                   H2 * std::log(H2 * (1 + S) / ((1 + H2) * S));
  return (W * std::atan(1 / W) + H * std::atan(1 / H) - std::sqrt(S) * std::atan(1 / std::sqrt(S)) +
          L / 4) /
         (glm::pi<double>() * W);
}
inline double coaxialDiscsF(double r1, double r2, double a) {
  const double R1 = r1 / a, R2 = r2 / a, X = 1 + (1 + R2 * R2) / (R1 * R1);
  return (X - std::sqrt(X * X - 4 * (R2 / R1) * (R2 / R1))) / 2;
}

}  // namespace rad::test
