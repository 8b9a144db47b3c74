#pragma once
// The per-format image readers and writers behind writeImage/readImage (include/radiosity/image.h).
// Writers write to `file` (a temporary chosen by writeFileAtomically) and name `displayName`, the
// path the user asked for, in their errors. Readers throw InputError naming the file when it
// is malformed or truncated (EXR's reader is the scene's: scene/io/exr_reader.h).

#include <radiosity/image.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rad {

/// 8-bit sRGB PNG, tone mapped by toneMapPixel. Throws std::runtime_error on a write failure.
void writePng(const std::filesystem::path& file, const Image& image, float exposureEV,
              const std::string& displayName);

/// 8-bit texels (`width` x `height`, rows from the top; `channels` 3: RGB, 4: RGBA) encoded as
/// PNG bytes. Throws std::runtime_error if encoding fails.
std::string encodePng(int width, int height, const std::vector<uint8_t>& texels, int channels = 3);
/// `image` tone mapped (toneMapPixel at exposureEV) and encoded as PNG bytes. Throws as
/// encodePng.
std::string encodeTonemappedPng(const Image& image, float exposureEV);

/// OpenEXR scanline file with R, G, B channels of the given type. Throws std::runtime_error on
/// a write failure.
void writeExr(const std::filesystem::path& file, const Image& image, ExrPixelType type,
              const std::string& displayName);

/// Portable float map: "PF" colour, little-endian (scale -1), rows stored bottom to top.
void writePfm(const std::filesystem::path& file, const Image& image,
              const std::string& displayName);
/// Reads colour ("PF") or grey ("Pf") PFM of either byte order; the magnitude of the scale is
/// ignored, its sign gives the byte order.
Image readPfm(const std::filesystem::path& file);

}  // namespace rad
