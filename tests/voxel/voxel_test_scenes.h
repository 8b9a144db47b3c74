#pragma once
// Scenes for the voxel method's tests, built by hand (independent of the loaders).

#include <radiosity/scene_builder.h>

#include <cmath>
#include <glm/gtc/constants.hpp>

#include "render/test_scenes.h"

namespace rad::test {

/// The inward-facing cube [0,1]^3 with one material for all faces.
inline Scene uniformCube(const Color& rho, const Color& emission) {
  SceneBuilder b("cube");
  const uint32_t m = b.addMaterial({"wall", rho, emission, false});
  addInwardCube(b, [m](int) { return m; });
  return b.build();
}

/// A UV sphere of radius r centred at c, faces pointing `inward` or outward.
inline void addSphere(SceneBuilder& b, const Vec3& c, float r, bool inward, uint32_t material,
                      uint32_t object, int rings = 24, int segments = 48) {
  auto point = [&](int i, int j) {
    const float theta = glm::pi<float>() * float(i) / float(rings);
    const float phi = 2.0f * glm::pi<float>() * float(j) / float(segments);
    return c + r * Vec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                        std::sin(theta) * std::sin(phi));
  };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      std::array<Vec3, 3> t1{point(i, j), point(i + 1, j), point(i + 1, j + 1)};
      std::array<Vec3, 3> t2{point(i, j), point(i + 1, j + 1), point(i, j + 1)};
      for (auto& t : {t1, t2}) {
        const Vec3 n = glm::cross(t[1] - t[0], t[2] - t[0]);
        const Vec3 out = (t[0] + t[1] + t[2]) / 3.0f - c;
        std::array<uint32_t, 3> ids;
        for (int k = 0; k < 3; ++k) ids[k] = b.addVertex(t[k], "sphere");
        if ((glm::dot(n, out) > 0.0f) == inward) std::swap(ids[1], ids[2]);
        b.addPolygon(ids, material, object, "sphere");
      }
    }
}

}  // namespace rad::test
