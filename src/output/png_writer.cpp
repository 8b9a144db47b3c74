#include <radiosity/atomic_file.h>

#include <fstream>
#include <stdexcept>
#include <vector>

#include "output/image_formats.h"

// The one translation unit of the library that holds stb_image_write's implementation.
// Its C-style "= { 0 }" initializers trip -Wextra; the warnings are stb's, not ours.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb_image_write.h>
#pragma GCC diagnostic pop

namespace rad {

namespace {

void appendBytes(void* context, void* data, int size) {
  auto* bytes = static_cast<std::vector<char>*>(context);
  const char* begin = static_cast<const char*>(data);
  bytes->insert(bytes->end(), begin, begin + size);
}

}  // namespace

std::string encodePng(int width, int height, const std::vector<uint8_t>& texels, int channels) {
  std::vector<char> encoded;
  if (!stbi_write_png_to_func(appendBytes, &encoded, width, height, channels, texels.data(),
                              width * channels))
    throw std::runtime_error("PNG encoding failed");
  return std::string(encoded.begin(), encoded.end());
}

std::string encodeTonemappedPng(const Image& image, float exposureEV) {
  std::vector<uint8_t> rgb(image.pixels.size() * 3);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const std::array<uint8_t, 3> p = toneMapPixel(image.pixels[i], exposureEV);
    rgb[3 * i + 0] = p[0];
    rgb[3 * i + 1] = p[1];
    rgb[3 * i + 2] = p[2];
  }
  return encodePng(image.width, image.height, rgb);
}

void writePng(const std::filesystem::path& file, const Image& image, float exposureEV,
              const std::string& displayName) {
  // Encoding to memory first keeps stb's FILE handling out and lets us check the write.
  std::string encoded;
  try {
    encoded = encodeTonemappedPng(image, exposureEV);
  } catch (const std::runtime_error&) {
    throw std::runtime_error("cannot write '" + displayName + "': PNG encoding failed");
  }
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(encoded.data(), std::streamsize(encoded.size()));
  out.close();
  if (out.fail()) throw std::runtime_error("cannot write '" + displayName + "': write failed");
}

}  // namespace rad
