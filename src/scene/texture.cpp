// Texture decoding (stb_image) and filtered lookups over a box-filtered pyramid (mip-mapping:
// L. Williams, "Pyramidal parametrics", SIGGRAPH 1983).
#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/process_memory.h>
#include <radiosity/texture.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iterator>

#include "core/binary_io.h"

// The library's own copy of stb_image, static so that it never meets another one at link time.
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#include <stb_image.h>
#pragma GCC diagnostic pop

namespace rad {

namespace {

constexpr int kMaxSide = 16384;
constexpr float kFullScale = 65535.0f;
constexpr uint64_t kMaxFileBytes = uint64_t(1) << 30;

uint16_t toTexel(float linear) {
  return uint16_t(std::lround(std::clamp(linear, 0.0f, 1.0f) * kFullScale));
}

int wrapIndex(int i, int n, TextureWrap wrap) {
  switch (wrap) {
    case TextureWrap::ClampToEdge:
      return std::clamp(i, 0, n - 1);
    case TextureWrap::MirroredRepeat: {
      const int period = 2 * n;
      int m = i % period;
      if (m < 0) m += period;
      return m < n ? m : period - 1 - m;
    }
    case TextureWrap::Repeat:
      break;
  }
  const int m = i % n;
  return m < 0 ? m + n : m;
}

// The next level of a pyramid: each texel the mean of the 2 x 2 (an odd side's last texel
// repeats) it covers, averaged in floats from the level below. Empty stays empty.
template <typename T>
std::vector<T> halved(const std::vector<T>& current, int w, int h) {
  if (current.empty()) return {};
  const int nw = (w + 1) / 2, nh = (h + 1) / 2;
  std::vector<T> next(size_t(nw) * size_t(nh));
  for (int y = 0; y < nh; ++y)
    for (int x = 0; x < nw; ++x) {
      T sum(0.0f);
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx)
          sum += current[size_t(std::min(2 * y + dy, h - 1)) * size_t(w) +
                         size_t(std::min(2 * x + dx, w - 1))];
      next[size_t(y) * size_t(nw) + size_t(x)] = 0.25f * sum;
    }
  return next;
}

}  // namespace

float srgbToLinear(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

float linearToSrgb(float linear) {
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

std::shared_ptr<const Texture> Texture::load(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open the texture (missing or unreadable)");
  std::vector<uint8_t> bytes;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    bytes.insert(bytes.end(), buffer, buffer + in.gcount());
    if (bytes.size() > kMaxFileBytes)
      throw InputError(path, fmt::format("texture larger than {} bytes", kMaxFileBytes));
  }
  return decode(bytes, path);
}

std::shared_ptr<const Texture> Texture::decode(std::span<const uint8_t> bytes,
                                               const std::string& name) {
  if (bytes.empty() || bytes.size() > size_t(INT32_MAX))
    throw InputError(name, "empty or oversized texture image");
  const auto* data = bytes.data();
  const int size = int(bytes.size());
  int w = 0, h = 0, channels = 0;
  if (!stbi_info_from_memory(data, size, &w, &h, &channels))
    throw InputError(name, fmt::format("not a PNG or JPEG image ({})", stbi_failure_reason()));
  if (w < 1 || h < 1 || w > kMaxSide || h > kMaxSide)
    throw InputError(name,
                     fmt::format("texture of {} x {} texels (at most {} a side)", w, h, kMaxSide));
  // While decoding: stb's texels (up to 6 B), the linear floats (12 B), the pyramid (8 B).
  requireMemory(double(w) * double(h) * 26.0, name,
                fmt::format("a texture of {} x {} texels", w, h), "use a smaller texture");
  // Grey and alpha or RGBA files keep their alpha (4 channels asked for); the rest RGB.
  const int want = channels == 2 || channels == 4 ? 4 : 3;
  std::vector<Color> linear(size_t(w) * size_t(h));
  std::vector<float> alpha(want == 4 ? linear.size() : 0);
  if (stbi_is_16_bit_from_memory(data, size)) {
    stbi_us* texels = stbi_load_16_from_memory(data, size, &w, &h, &channels, want);
    if (!texels) throw InputError(name, fmt::format("cannot decode ({})", stbi_failure_reason()));
    for (size_t i = 0; i < linear.size(); ++i) {
      const stbi_us* t = texels + size_t(want) * i;
      for (int c = 0; c < 3; ++c) linear[i][c] = srgbToLinear(t[c] / 65535.0f);
      if (want == 4) alpha[i] = t[3] / 65535.0f;
    }
    stbi_image_free(texels);
  } else {
    stbi_uc* texels = stbi_load_from_memory(data, size, &w, &h, &channels, want);
    if (!texels) throw InputError(name, fmt::format("cannot decode ({})", stbi_failure_reason()));
    std::array<float, 256> table;
    for (int v = 0; v < 256; ++v) table[size_t(v)] = srgbToLinear(float(v) / 255.0f);
    for (size_t i = 0; i < linear.size(); ++i) {
      const stbi_uc* t = texels + size_t(want) * i;
      for (int c = 0; c < 3; ++c) linear[i][c] = table[t[c]];
      if (want == 4) alpha[i] = float(t[3]) / 255.0f;
    }
    stbi_image_free(texels);
  }
  return std::make_shared<const Texture>(w, h, std::move(linear), name, std::move(alpha));
}

Texture::Texture(int width, int height, std::vector<Color> linear, std::string name,
                 std::vector<float> alpha)
    : width_(width), height_(height), name_(std::move(name)) {
  if (std::all_of(alpha.begin(), alpha.end(), [](float a) { return a >= 1.0f; })) alpha.clear();
  Level base = levelOf(width, height, linear, alpha);
  digest_ = checksum(reinterpret_cast<const char*>(base.texels.data()),
                     base.texels.size() * sizeof(uint16_t));
  if (!base.alpha.empty())
    digest_ ^= checksum(reinterpret_cast<const char*>(base.alpha.data()),
                        base.alpha.size() * sizeof(uint16_t));
  levels_.push_back(std::move(base));
  int w = width, h = height;
  while (w > 1 || h > 1) {
    linear = halved(linear, w, h);
    alpha = halved(alpha, w, h);
    w = (w + 1) / 2;
    h = (h + 1) / 2;
    levels_.push_back(levelOf(w, h, linear, alpha));
  }
}

Color Texture::Level::at(int x, int y) const {
  const size_t i = 3 * (size_t(y) * size_t(width) + size_t(x));
  return Color(texels[i], texels[i + 1], texels[i + 2]) / kFullScale;
}

float Texture::Level::alphaAt(int x, int y) const {
  return float(alpha[size_t(y) * size_t(width) + size_t(x)]) / kFullScale;
}

std::vector<uint8_t> Texture::srgb8() const {
  const Level& base = levels_.front();
  std::vector<uint8_t> out(base.texels.size());
  for (size_t i = 0; i < out.size(); ++i) {
    const float encoded = linearToSrgb(float(base.texels[i]) / kFullScale);
    out[i] = uint8_t(std::lround(std::clamp(encoded, 0.0f, 1.0f) * 255.0f));
  }
  return out;
}

Color Texture::mean() const {
  return levels_.back().at(0, 0);
}

std::shared_ptr<const Texture> Texture::greyAsAlpha() const {
  const Level& base = levels_.front();
  std::vector<Color> linear(size_t(width_) * size_t(height_));
  std::vector<float> alpha(linear.size());
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      const size_t i = size_t(y) * size_t(width_) + size_t(x);
      linear[i] = base.at(x, y);
      alpha[i] = linearToSrgb(linear[i].r);
    }
  return std::make_shared<const Texture>(width_, height_, std::move(linear), name_,
                                         std::move(alpha));
}

float Texture::meanAlpha() const {
  return hasAlpha() ? levels_.back().alphaAt(0, 0) : 1.0f;
}

Texture::Level Texture::levelOf(int width, int height, const std::vector<Color>& linear,
                                const std::vector<float>& alpha) {
  Level level{width, height, std::vector<uint16_t>(3 * linear.size()), {}};
  for (size_t i = 0; i < linear.size(); ++i)
    for (int c = 0; c < 3; ++c) level.texels[3 * i + size_t(c)] = toTexel(linear[i][c]);
  for (float a : alpha) level.alpha.push_back(toTexel(a));
  return level;
}

template <typename Lookup>
auto Texture::bilinear(const Level& level, Vec2 uv, TextureWrap wrapU, TextureWrap wrapV,
                       Lookup&& at) const {
  const float x = uv.x * float(level.width) - 0.5f, y = uv.y * float(level.height) - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const float tx = x - fx, ty = y - fy;
  const int x0 = int(fx), y0 = int(fy);
  const int xa = wrapIndex(x0, level.width, wrapU), xb = wrapIndex(x0 + 1, level.width, wrapU);
  const int ya = wrapIndex(y0, level.height, wrapV), yb = wrapIndex(y0 + 1, level.height, wrapV);
  return (1.0f - ty) * ((1.0f - tx) * at(level, xa, ya) + tx * at(level, xb, ya)) +
         ty * ((1.0f - tx) * at(level, xa, yb) + tx * at(level, xb, yb));
}

template <typename Lookup>
auto Texture::filtered(Vec2 uv, float footprint, TextureWrap wrapU, TextureWrap wrapV,
                       Lookup&& at) const {
  const int top = int(levels_.size()) - 1;
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return at(levels_.back(), 0, 0);
  // Coordinates far outside [0, 1] lose the texel's fraction in floats: fold repeats first.
  if (wrapU == TextureWrap::Repeat) uv.x -= std::floor(uv.x);
  if (wrapV == TextureWrap::Repeat) uv.y -= std::floor(uv.y);
  const float texels = footprint * float(std::max(width_, height_));
  const float lod = texels > 1.0f ? std::log2(texels) : 0.0f;
  if (lod >= float(top)) return at(levels_.back(), 0, 0);
  const int l0 = int(lod);
  const float t = lod - float(l0);
  const auto a = bilinear(levels_[size_t(l0)], uv, wrapU, wrapV, at);
  if (t <= 0.0f) return a;
  return (1.0f - t) * a + t * bilinear(levels_[size_t(l0 + 1)], uv, wrapU, wrapV, at);
}

Color Texture::sample(Vec2 uv, float footprint, TextureWrap wrapU, TextureWrap wrapV) const {
  return filtered(uv, footprint, wrapU, wrapV,
                  [](const Level& l, int x, int y) { return l.at(x, y); });
}

float Texture::sampleAlpha(Vec2 uv, float footprint, TextureWrap wrapU, TextureWrap wrapV) const {
  if (!hasAlpha()) return 1.0f;
  return filtered(uv, footprint, wrapU, wrapV,
                  [](const Level& l, int x, int y) { return l.alphaAt(x, y); });
}

size_t Texture::memoryBytes() const {
  size_t bytes = 0;
  for (const Level& l : levels_) bytes += (l.texels.size() + l.alpha.size()) * sizeof(uint16_t);
  return bytes;
}

Vec2 TextureMap::apply(Vec2 uv) const {
  return {transform[0] * uv.x + transform[1] * uv.y + transform[4],
          transform[2] * uv.x + transform[3] * uv.y + transform[5]};
}

// The transform scales the footprint by its largest stretch.
float TextureMap::stretch() const {
  return std::max(std::hypot(transform[0], transform[2]), std::hypot(transform[1], transform[3]));
}

Color TextureMap::at(Vec2 uv, float footprint) const {
  if (!texture) return Color(1.0f);
  return texture->sample(apply(uv), footprint * stretch(), wrapU, wrapV);
}

float TextureMap::alphaAt(Vec2 uv, float footprint) const {
  if (!texture) return 1.0f;
  return texture->sampleAlpha(apply(uv), footprint * stretch(), wrapU, wrapV);
}

bool TextureMap::operator==(const TextureMap& other) const {
  return texture == other.texture && wrapU == other.wrapU && wrapV == other.wrapV &&
         std::equal(std::begin(transform), std::end(transform), std::begin(other.transform));
}

}  // namespace rad
