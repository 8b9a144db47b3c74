#pragma once
// Hand-built scenes for the path tracer tests (independent of the scene loaders).

#include <gtest/gtest.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/path_tracer.h>
#include <radiosity/scene_builder.h>
#include <radiosity/surface_solution.h>

#include <array>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <map>
#include <optional>
#include <string>

namespace rad::test {

/// docs/references.md 1(d): the view factor from a point to a parallel a x b rectangle at height c,
/// the point's normal through a corner (Siegel & Howell via EES FDiff_1).
inline double cornerElementF(double a, double b, double c) {
  const double X = a / c, Y = b / c;
  return (X / std::sqrt(1 + X * X) * std::atan(Y / std::sqrt(1 + X * X)) +
          Y / std::sqrt(1 + Y * Y) * std::atan(X / std::sqrt(1 + Y * Y))) /
         (2 * glm::pi<double>());
}

/// 1(d) by superposition: from the point (pu, pv) of a plane to the rectangle [u0, u1] x [v0, v1]
/// of the parallel plane at height c facing it.
inline double pointToParallelRectangleF(double pu, double pv, double u0, double u1, double v0,
                                        double v1, double c) {
  auto corner = [c](double u, double v) {
    const double f = cornerElementF(std::abs(u), std::abs(v), c);
    return (u < 0) != (v < 0) ? -f : f;
  };
  return corner(u1 - pu, v1 - pv) - corner(u0 - pu, v1 - pv) - corner(u1 - pu, v0 - pv) +
         corner(u0 - pu, v0 - pv);
}

/// Adds the quad p0 p1 p2 p3 (a planar, convex outline in either winding), oriented so that its
/// front faces `front`.
inline void addQuadFacing(SceneBuilder& b, std::array<Vec3, 4> corners, const Vec3& front,
                          uint32_t material, uint32_t object) {
  const Vec3 n = glm::cross(corners[1] - corners[0], corners[2] - corners[0]);
  if (glm::dot(n, front) < 0.0f) std::swap(corners[1], corners[3]);
  std::array<uint32_t, 4> ids{};
  for (int k = 0; k < 4; ++k) ids[k] = b.addVertex(corners[k], "test");
  b.addPolygon(ids, material, object, "test");
}

/// Axis-aligned square of side `size` centred at `c`, in the plane normal to axis `axis`.
inline std::array<Vec3, 4> axisSquare(const Vec3& c, int axis, float size) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  std::array<Vec3, 4> q;
  const float h = 0.5f * size;
  const float su[4] = {-h, h, h, -h}, sv[4] = {-h, -h, h, h};
  for (int k = 0; k < 4; ++k) {
    q[k] = c;
    q[k][u] += su[k];
    q[k][v] += sv[k];
  }
  return q;
}

/// The unit cube [0,1]^3 seen from inside: six faces (one object each) facing inward.
/// `materialOf(face)` gives each face's material index (faces 0..5: -x, +x, -y, +y, -z, +z).
template <class MaterialOf>
void addInwardCube(SceneBuilder& b, MaterialOf materialOf) {
  int face = 0;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side, ++face) {
      Vec3 centre(0.5f);
      centre[axis] = float(side);
      Vec3 inward(0.0f);
      inward[axis] = side == 0 ? 1.0f : -1.0f;
      const uint32_t object = b.addObject("face" + std::to_string(face));
      addQuadFacing(b, axisSquare(centre, axis, 1.0f), inward, materialOf(face), object);
    }
}

/// The unit cube seen from inside, lit by its ceiling (face 3, the lamp's reflectance and
/// radiance given), with a red two-sided wall (face 0, x = 0) and grey one-sided walls: what the
/// mesh exports are checked on.
inline Scene litCubeRoom(const Color& lampRho, const Color& lampEmission) {
  SceneBuilder b("room");
  const uint32_t wall = b.addMaterial({"wall", Color(0.6f), Color(0.0f), false});
  const uint32_t red = b.addMaterial({"red", Color(0.7f, 0.1f, 0.1f), Color(0.0f), true});
  const uint32_t lamp = b.addMaterial({"lamp", lampRho, lampEmission, false});
  addInwardCube(b, [&](int face) { return face == 3 ? lamp : face == 0 ? red : wall; });
  return b.build();
}

/// The unit cube seen from inside, every face of reflectance `rho`, face 0 emitting radiosity
/// E = 1 (Ke = 1 / pi): a closed room whose sum of A B is sum A E / (1 - rho)
/// (docs/references.md 3.1).
inline Scene closedCube(float rho) {
  SceneBuilder b("cube");
  const uint32_t wall = b.addMaterial({"wall", Color(rho), Color(0.0f), false});
  const uint32_t lamp = b.addMaterial({"lamp", Color(rho), Color(1.0f / glm::pi<float>()), false});
  addInwardCube(b, [&](int face) { return face == 0 ? lamp : wall; });
  return b.build();
}

/// Patch settings for about `patches` patches, with no form-factor cache on disk.
inline PatchRadiositySettings uncachedPatchSettings(size_t patches) {
  PatchRadiositySettings s;
  s.targetPatches = patches;
  s.cacheDir.clear();
  return s;
}

/// An emitting square [-1, 1]^2 at z = 2 facing down (Ke 1) over a floor [-1, 1]^2 at z = 0, both
/// black; with `sheetAlpha`, a black Blend sheet of that alpha at z = 1, wider than both (every
/// line between them crosses it).
inline Scene lampOverFloor(std::optional<float> sheetAlpha) {
  SceneBuilder b("lamp over floor");
  const uint32_t lamp = b.addMaterial({"lamp", Color(0.0f), Color(1.0f)});
  const uint32_t black = b.addMaterial({"black", Color(0.0f)});
  addQuadFacing(b, axisSquare(Vec3(0, 0, 2), 2, 2.0f), Vec3(0, 0, -1), lamp, b.addObject("lamp"));
  addQuadFacing(b, axisSquare(Vec3(0, 0, 0), 2, 2.0f), Vec3(0, 0, 1), black, b.addObject("floor"));
  if (sheetAlpha) {
    Material sheet{"sheet", Color(0.0f)};
    sheet.alphaMode = AlphaMode::Blend;
    sheet.alpha = *sheetAlpha;
    addQuadFacing(b, axisSquare(Vec3(0, 0, 1), 2, 3.0f), Vec3(0, 0, -1), b.addMaterial(sheet),
                  b.addObject("sheet"));
  }
  return b.build();
}

/// The per-object means of the object called `name` in `solution` (a test failure if none).
inline ObjectRadiometry objectNamed(const SurfaceSolution& solution, const std::string& name) {
  for (const ObjectRadiometry& o : solution.objectRadiometry())
    if (o.name == name) return o;
  ADD_FAILURE() << "no object " << name;
  return {};
}

/// The path tracer's per-object means, by object name: the reference the radiosity methods are
/// compared with. Where its points fall matters more than how many paths each gets (shadows make
/// irradiance discontinuous), so callers ask for many points and few paths.
inline std::map<std::string, ObjectRadiometry> tracedObjectMeans(const Scene& scene, int points,
                                                                 int pathsPerPoint, uint64_t seed) {
  PathTracerSettings settings;
  settings.samplesPerPixel = pathsPerPoint;
  settings.seed = seed;
  std::map<std::string, ObjectRadiometry> means;
  for (const ObjectRadiometry& o : estimateObjectRadiometry(scene, points, settings))
    means[o.name] = o;
  return means;
}

}  // namespace rad::test
