#pragma once
// Reading OpenEXR images: what an environment sky (sky.h) is read from, and readImage's EXR.

#include <radiosity/image.h>

#include <filesystem>

namespace rad {

/// Reads the R, G, B channels (half, float or uint, converted to float) of an EXR file; a file
/// with only a Y channel reads as grey. Alpha and other channels are ignored. Throws InputError
/// naming the file when it is malformed, truncated or larger than 2^30 pixels.
Image readExr(const std::filesystem::path& file);

}  // namespace rad
