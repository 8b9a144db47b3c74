#include "scene/builtin/builtin_shapes.h"

#include <array>

namespace rad {

void addBox(SceneBuilder& b, Vec3 lo, Vec3 hi, uint32_t material, uint32_t object, BoxSide side,
            bool bottom) {
  const std::string where = b.scene().name;
  auto v = [&](int i, int j, int k) {
    return b.addVertex(Vec3(i ? hi.x : lo.x, j ? hi.y : lo.y, k ? hi.z : lo.z), where);
  };
  const std::array<std::array<int, 12>, 6> quads{{
      {0, 0, 0, 0, 0, 1, 0, 1, 1, 0, 1, 0},  // -x
      {1, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1},  // +x
      {0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1},  // -y (bottom)
      {0, 1, 0, 0, 1, 1, 1, 1, 1, 1, 1, 0},  // +y
      {0, 0, 0, 0, 1, 0, 1, 1, 0, 1, 0, 0},  // -z
      {0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1},  // +z
  }};
  for (size_t f = 0; f < quads.size(); ++f) {
    if (f == 2 && !bottom) continue;
    const auto& q = quads[f];
    std::array<uint32_t, 4> c{v(q[0], q[1], q[2]), v(q[3], q[4], q[5]), v(q[6], q[7], q[8]),
                              v(q[9], q[10], q[11])};
    if (side == BoxSide::Inside) std::swap(c[1], c[3]);
    b.addPolygon(c, material, object, where);
  }
}

void addQuad(SceneBuilder& b, Vec3 a, Vec3 c1, Vec3 c2, Vec3 c3, uint32_t material,
             uint32_t object) {
  const std::string& where = b.scene().name;
  const std::array<uint32_t, 4> c{b.addVertex(a, where), b.addVertex(c1, where),
                                  b.addVertex(c2, where), b.addVertex(c3, where)};
  b.addPolygon(c, material, object, where);
}

}  // namespace rad
