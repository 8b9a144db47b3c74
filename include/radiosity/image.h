#pragma once
// Images of linear radiance and the files they are written to: PNG (tone mapped), EXR and PFM
// (linear floats). Every writer goes to a temporary file in the target directory and renames
// it, so a failed or interrupted run never leaves a partial image.

#include <radiosity/types.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace rad {

/// Row-major RGB pixels, row 0 at the top.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<Color> pixels;

  Image() = default;
  Image(int w, int h) : width(w), height(h), pixels(size_t(w) * size_t(h), Color(0.0f)) {}
  Color& at(int x, int y) { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
  const Color& at(int x, int y) const { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
};

enum class ExrPixelType { Half, Float };

struct ImageWriteOptions {
  float exposureEV = 0.0f;  ///< PNG only: radiance is scaled by 2^exposureEV before the sRGB curve
  ExrPixelType exrPixelType = ExrPixelType::Half;
};

/// True for the extensions writeImage knows: .png, .exr, .pfm (case-insensitive).
bool isSupportedImageFormat(const std::string& path);

/// Writes `image` in the format its extension names. Throws InputError for an unsupported
/// extension (naming it and the supported ones) and std::runtime_error when the file cannot be
/// written; in both cases no file is left at `path`.
void writeImage(const std::string& path, const Image& image, const ImageWriteOptions& options = {});

/// Reads a linear EXR or PFM image. Throws InputError if it is missing or malformed.
Image readImage(const std::string& path);

/// The sRGB transfer curve (IEC 61966-2-1) of a linear value in [0, 1].
float srgbEncode(float linear);
/// PNG tone mapping of one pixel: scale by 2^exposureEV, sRGB curve, clamp, round to 8 bits.
std::array<uint8_t, 3> toneMapPixel(const Color& radiance, float exposureEV);

}  // namespace rad
