#include <radiosity/atomic_file.h>
#include <radiosity/error.h>
#include <radiosity/image.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <stdexcept>

#include "output/image_formats.h"
#include "scene/io/exr_reader.h"

namespace rad {

namespace {

namespace fs = std::filesystem;

std::string lowerCaseExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

std::string unsupportedMessage(const std::string& ext, const char* supported) {
  return "unsupported image format '" + (ext.empty() ? std::string("(no extension)") : ext) +
         "' (supported: " + supported + ")";
}

}  // namespace

bool isSupportedImageFormat(const std::string& path) {
  const std::string ext = lowerCaseExtension(path);
  return ext == ".png" || ext == ".exr" || ext == ".pfm";
}

void writeImage(const std::string& path, const Image& image, const ImageWriteOptions& options) {
  const std::string ext = lowerCaseExtension(path);
  if (!isSupportedImageFormat(path))
    throw InputError(path, unsupportedMessage(ext, ".png .exr .pfm"));
  // An inconsistent Image is the caller's bug, not the user's input.
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != size_t(image.width) * size_t(image.height))
    throw std::invalid_argument("writeImage: image of " + std::to_string(image.width) + " x " +
                                std::to_string(image.height) + " with " +
                                std::to_string(image.pixels.size()) + " pixels");

  writeFileAtomically(path, [&](const fs::path& temporary) {
    if (ext == ".png")
      writePng(temporary, image, options.exposureEV, path);
    else if (ext == ".exr")
      writeExr(temporary, image, options.exrPixelType, path);
    else
      writePfm(temporary, image, path);
  });
}

Image readImage(const std::string& path) {
  const std::string ext = lowerCaseExtension(path);
  if (ext != ".exr" && ext != ".pfm") throw InputError(path, unsupportedMessage(ext, ".exr .pfm"));
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw InputError(path, "cannot open: no such file");
  return ext == ".exr" ? readExr(path) : readPfm(path);
}

}  // namespace rad
