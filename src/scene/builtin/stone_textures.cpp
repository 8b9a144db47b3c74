#include "scene/builtin/stone_textures.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <string>
#include <vector>

namespace rad {

namespace {

// A well-mixed 32-bit hash (Wellons' lowbias32) of a few integers, as a value in [0, 1).
float hashUnit(uint32_t a, uint32_t b = 0, uint32_t c = 0) {
  uint32_t x = a * 0x9E3779B9u ^ (b + 0x7F4A7C15u) * 0x85EBCA6Bu ^ (c + 0x165667B1u) * 0xC2B2AE35u;
  x ^= x >> 16;
  x *= 0x7FEB352Du;
  x ^= x >> 15;
  x *= 0x846CA68Bu;
  x ^= x >> 16;
  return float(x >> 8) / float(1u << 24);
}

// Texel grain: a few percent of brightness, different at every texel.
float grain(int x, int y, uint32_t seed) {
  return 0.97f + 0.06f * hashUnit(uint32_t(x), uint32_t(y), seed);
}

}  // namespace

std::shared_ptr<const Texture> makeFloorTiles(int size, int tiles) {
  const int tile = size / tiles, grout = std::max(2, tile / 40);
  const Color light(0.95f, 0.93f, 0.88f), dark(0.72f, 0.68f, 0.62f), joint(0.50f, 0.49f, 0.46f);
  std::vector<Color> texels(size_t(size) * size_t(size));
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const int i = x / tile, j = y / tile;
      const bool inGrout = x % tile < grout || y % tile < grout;
      const float variation = 0.94f + 0.06f * hashUnit(uint32_t(i), uint32_t(j), 1u);
      const Color tone = inGrout ? joint : ((i + j) % 2 ? light : dark) * variation;
      texels[size_t(y) * size_t(size) + size_t(x)] = glm::min(tone * grain(x, y, 2u), Color(1.0f));
    }
  return std::make_shared<const Texture>(size, size, std::move(texels), "floor_tiles");
}

std::shared_ptr<const Texture> makeAshlar(int size, int rows) {
  const int rowHeight = size / rows, blockLength = 2 * rowHeight;
  const int joint = std::max(2, rowHeight / 16);
  const Color stone(0.86f, 0.82f, 0.74f), mortar(0.60f, 0.58f, 0.54f);
  std::vector<Color> texels(size_t(size) * size_t(size));
  for (int y = 0; y < size; ++y) {
    const int row = y / rowHeight;
    const int offset = row % 2 ? blockLength / 2 : 0;  // running bond
    for (int x = 0; x < size; ++x) {
      const int along = (x + offset) % size;
      const int block = along / blockLength;
      const bool inJoint = y % rowHeight < joint || along % blockLength < joint;
      const float variation = 0.88f + 0.12f * hashUnit(uint32_t(block), uint32_t(row), 3u);
      const Color tone = inJoint ? mortar : stone * variation;
      texels[size_t(y) * size_t(size) + size_t(x)] = glm::min(tone * grain(x, y, 4u), Color(1.0f));
    }
  }
  return std::make_shared<const Texture>(size, size, std::move(texels), "ashlar");
}

void mapPlanar(SceneBuilder& builder, uint32_t material, float period) {
  const Scene& scene = builder.scene();
  for (const Face& face : scene.faces) {
    if (face.material != material) continue;
    const Vec3 n = glm::abs(face.normal);
    for (uint32_t t = face.firstTriangle; t < face.firstTriangle + face.triangleCount; ++t)
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = scene.triangles[t][k];
        const Vec3 p = scene.positions[v] / period;
        // v runs down the texture and y up the world: walls take -y, so rows stay level.
        const Vec2 uv = n.y >= n.x && n.y >= n.z ? Vec2(p.x, p.z)
                        : n.x >= n.z             ? Vec2(p.z, -p.y)
                                                 : Vec2(p.x, -p.y);
        builder.setTexcoord(v, uv, scene.name);
      }
  }
}

void applyTexture(Material& material, std::shared_ptr<const Texture> texture) {
  const Color mean = texture->mean();
  material.rho = glm::min(material.rho / glm::max(mean, Color(1e-3f)), Color(kMaxReflectance));
  material.rhoTexture.texture = std::move(texture);
}

}  // namespace rad
