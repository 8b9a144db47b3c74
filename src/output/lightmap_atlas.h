#pragma once
// A lightmap atlas: the solved irradiance stored in one square texture over the scene's own
// triangles, the way game engines keep baked light. Each side of each planar face gets a chart
// (the face projected onto its plane at one texel density for the whole scene), the charts are
// packed with stb_rect_pack, and every chart's texels, its gutter included, hold the light of
// the nearest point of its face, so that bilinear filtering never reads an empty texel.

#include <radiosity/image.h>
#include <radiosity/scene.h>
#include <radiosity/surface_solution.h>

#include <cstdint>
#include <vector>

namespace rad {

/// One side of one face, laid out in the atlas.
struct LightmapChart {
  uint32_t face = 0;
  bool backSide = false;
  int x = 0, y = 0;               ///< its corner in the atlas (texels, row 0 at the top)
  int width = 0, height = 0;      ///< texels, gutters included
  Vec3 origin{0.0f};              ///< the face's plane point at the chart's inner corner
  Vec3 uAxis{0.0f}, vAxis{0.0f};  ///< unit axes in the face's plane, along x and y
};

struct LightmapAtlas {
  int size = 0;                ///< texels on a side
  float texelsPerUnit = 0.0f;  ///< the one density of every chart (texels per scene unit)
  std::vector<LightmapChart> charts;
  /// Texels of margin around each chart's face: bilinear filtering at the outline reads
  /// within half a texel of it, and every chart's margin is its own.
  static constexpr int kGutter = 2;

  /// Where `point` (on the chart's face) lies in the atlas, as glTF texture coordinates
  /// ((0, 0) the top-left corner, (1, 1) the bottom-right).
  Vec2 texcoordOf(const LightmapChart& chart, const Vec3& point) const;
};

/// Memory an atlas takes while exported, per texel: its irradiance and radiance images
/// (12 B each), the 8-bit copy and its PNG, and the EXR writer's buffer.
inline constexpr double kLightmapBytesPerTexel = 48.0;

/// Lays out a chart for the front of every face, and for the back of two-sided ones, at the
/// largest density that packs them into `size` x `size` texels. Throws InputError when even
/// the smallest charts do not fit (a face needs at least 5 x 5 texels with its gutters).
LightmapAtlas packLightmapAtlas(const Scene& scene, int size);

/// The atlas's images: per texel, the irradiance H (W per square scene unit) and the radiance
/// leaving the surface (what a picture shows), both linear. Texels between charts stay 0.
struct LightmapImages {
  Image irradiance;
  Image radiance;
};
/// Evaluates `solution` at every chart texel's point (the nearest point of its face), in
/// parallel.
LightmapImages shadeLightmapAtlas(const LightmapAtlas& atlas, const SurfaceSolution& solution);

/// The scene's own triangles, one group per object, a vertex per corner of each chart (two
/// charts never share one) with its atlas coordinates in LitMesh::lightmapTexcoords; the back
/// side of a two-sided face wound the other way. Colours are left black.
LitMesh lightmappedMesh(const Scene& scene, const LightmapAtlas& atlas);

}  // namespace rad
