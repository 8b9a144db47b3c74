#pragma once
// Colour textures of materials (base colour, emission): decoded from PNG or JPEG, kept in linear
// colour (the files are sRGB-encoded), with a box-filtered pyramid so that a lookup can average
// over a footprint of any size: a pixel's (renders), a patch's or a voxel side's (the solve).
// An image's alpha channel (coverage, glTF alphaMode) is kept beside it, linear as stored.

#include <radiosity/types.h>

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace rad {

/// How texture coordinates outside [0, 1] map into the image (glTF's sampler wrap modes).
enum class TextureWrap { Repeat, ClampToEdge, MirroredRepeat };

class Texture {
 public:
  /// Decodes a PNG or JPEG file (8 or 16 bits, grey or RGB, with or without alpha; alpha is kept
  /// only where some texel is below 1). Throws InputError
  /// naming `path` for a file that is missing, not an image, or larger than 16384 texels a side.
  static std::shared_ptr<const Texture> load(const std::string& path);
  /// The same from encoded bytes in memory (a GLB's embedded image); `name` names it in errors.
  static std::shared_ptr<const Texture> decode(std::span<const uint8_t> bytes,
                                               const std::string& name);
  /// From linear RGB texels, row by row from the top (v = 0) of the image, and their alpha
  /// (empty, or all 1: none; else one per texel, in [0, 1]).
  Texture(int width, int height, std::vector<Color> linear, std::string name,
          std::vector<float> alpha = {});

  int width() const { return width_; }
  int height() const { return height_; }
  const std::string& name() const { return name_; }
  /// The image's mean (its pyramid's top), linear.
  Color mean() const;
  /// True if some texel's alpha is below 1.
  bool hasAlpha() const { return !levels_.front().alpha.empty(); }
  /// The same image with the red channel's values as the file held them (sRGB-encoded again) for
  /// its alpha: an OBJ map_d of grey levels.
  std::shared_ptr<const Texture> greyAsAlpha() const;
  /// The alpha channel's mean (1 without one).
  float meanAlpha() const;
  /// The image as 8-bit sRGB RGB texels, rows from the top (what an exported glTF embeds).
  std::vector<uint8_t> srgb8() const;
  /// Linear colour at (u, v) (u across, v down from the top, as glTF and OBJ after its flip),
  /// averaged over a square footprint `footprint` wide in texture coordinates (0: one texel,
  /// bilinear), trilinear between the pyramid's levels.
  Color sample(Vec2 uv, float footprint, TextureWrap wrapU, TextureWrap wrapV) const;
  /// The alpha channel at (u, v), filtered as sample() filters colour (1 without one).
  float sampleAlpha(Vec2 uv, float footprint, TextureWrap wrapU, TextureWrap wrapV) const;
  /// Bytes held (every level).
  size_t memoryBytes() const;
  /// A hash of the texels: caches and solution files keyed by the scene know a changed image.
  uint64_t digest() const { return digest_; }

 private:
  struct Level {
    int width = 0, height = 0;
    std::vector<uint16_t> texels;  ///< RGB, linear, 65535 = 1
    std::vector<uint16_t> alpha;   ///< one a texel, 65535 = 1; empty: opaque
    Color at(int x, int y) const;
    float alphaAt(int x, int y) const;
  };
  static Level levelOf(int width, int height, const std::vector<Color>& linear,
                       const std::vector<float>& alpha);
  template <typename Lookup>
  auto bilinear(const Level& level, Vec2 uv, TextureWrap wrapU, TextureWrap wrapV,
                Lookup&& at) const;
  template <typename Lookup>
  auto filtered(Vec2 uv, float footprint, TextureWrap wrapU, TextureWrap wrapV, Lookup&& at) const;

  int width_ = 0, height_ = 0;
  uint64_t digest_ = 0;
  std::string name_;
  std::vector<Level> levels_;
};

/// sRGB-encoded value in [0, 1] to linear (IEC 61966-2-1), and back.
float srgbToLinear(float encoded);
float linearToSrgb(float linear);

/// A texture as a material uses it: the image, how coordinates wrap, and the 2D affine map
/// (glTF's KHR_texture_transform, OBJ's -o and -s) applied to a vertex's coordinates first.
struct TextureMap {
  std::shared_ptr<const Texture> texture;
  TextureWrap wrapU = TextureWrap::Repeat, wrapV = TextureWrap::Repeat;
  /// uv' = (a b; c d) uv + (e f), as offset, rotation and scale compose in KHR_texture_transform.
  float transform[6] = {1.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f};

  explicit operator bool() const { return texture != nullptr; }
  Vec2 apply(Vec2 uv) const;
  /// The texture's colour at a vertex coordinate, over a footprint as Texture::sample takes it.
  Color at(Vec2 uv, float footprint) const;
  /// Its alpha there (1 for none).
  float alphaAt(Vec2 uv, float footprint) const;
  bool operator==(const TextureMap& other) const;

 private:
  float stretch() const;
};

}  // namespace rad
