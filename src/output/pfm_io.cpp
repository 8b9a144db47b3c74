// Portable float map, as defined by Paul Debevec's HDRShop notes ("PFM Portable Float Map"):
// "PF" (RGB) or "Pf" (grey), then width and height, then a scale whose sign gives the byte order
// (negative: little-endian), each followed by one whitespace character, then 32-bit floats with
// the rows stored bottom to top.
#include <radiosity/error.h>

#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <vector>

#include "output/image_formats.h"

namespace rad {

namespace {

constexpr uint64_t kMaxPixels = uint64_t(1) << 30;

uint32_t byteSwap(uint32_t v) {
  return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
}

float floatFromBytes(const char* bytes, bool littleEndian) {
  uint32_t bits;
  std::memcpy(&bits, bytes, 4);
  if (littleEndian != (std::endian::native == std::endian::little)) bits = byteSwap(bits);
  return std::bit_cast<float>(bits);
}

// Reads the header field by field over the raw bytes, because the pixel data follows the
// single whitespace after the scale and a stream extractor could swallow a data byte.
class HeaderCursor {
 public:
  HeaderCursor(const std::vector<char>& bytes, const std::string& name)
      : bytes_(bytes), name_(name) {}

  std::string token(const char* what) {
    while (pos_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[pos_]))) ++pos_;
    const size_t start = pos_;
    while (pos_ < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[pos_]))) ++pos_;
    if (start == pos_ || pos_ >= bytes_.size())
      throw InputError(name_, std::string("truncated PFM header: missing ") + what);
    return std::string(bytes_.data() + start, pos_ - start);
  }
  /// Skips the one whitespace byte that ends the header.
  size_t dataStart() const { return pos_ + 1; }

 private:
  const std::vector<char>& bytes_;
  const std::string& name_;
  size_t pos_ = 0;
};

uint64_t parseDimension(const std::string& text, const char* what, const std::string& name) {
  if (text.empty() || text.size() > 9 ||
      text.find_first_not_of("0123456789") != std::string::npos || std::stoull(text) == 0)
    throw InputError(name,
                     std::string("PFM ") + what + " '" + text + "' is not a positive integer");
  return std::stoull(text);
}

}  // namespace

void writePfm(const std::filesystem::path& file, const Image& image,
              const std::string& displayName) {
  const std::string header =
      "PF\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n-1.0\n";
  std::vector<char> data(header.begin(), header.end());
  data.reserve(header.size() + image.pixels.size() * 12);
  for (int y = image.height - 1; y >= 0; --y) {
    for (int x = 0; x < image.width; ++x) {
      const Color& p = image.at(x, y);
      for (int c = 0; c < 3; ++c) {
        uint32_t bits = std::bit_cast<uint32_t>(p[c]);
        if constexpr (std::endian::native != std::endian::little) bits = byteSwap(bits);
        char bytes[4];
        std::memcpy(bytes, &bits, 4);
        data.insert(data.end(), bytes, bytes + 4);
      }
    }
  }
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(data.data(), std::streamsize(data.size()));
  out.close();
  if (out.fail()) throw std::runtime_error("cannot write '" + displayName + "': write failed");
}

Image readPfm(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(name, "cannot open");
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                std::istreambuf_iterator<char>());

  HeaderCursor cursor(bytes, name);
  const std::string magic = cursor.token("the PF/Pf magic");
  if (magic != "PF" && magic != "Pf")
    throw InputError(
        name, "not a PFM file (starts with '" + magic.substr(0, 8) + "', expected 'PF' or 'Pf')");
  const int channels = magic == "PF" ? 3 : 1;
  const uint64_t width = parseDimension(cursor.token("the width"), "width", name);
  const uint64_t height = parseDimension(cursor.token("the height"), "height", name);
  const std::string scaleText = cursor.token("the scale");
  char* end = nullptr;
  const double scale = std::strtod(scaleText.c_str(), &end);
  if (end != scaleText.c_str() + scaleText.size() || !std::isfinite(scale) || scale == 0.0)
    throw InputError(name, "PFM scale '" + scaleText + "' is not a non-zero number");
  if (width * height > kMaxPixels)
    throw InputError(name, "PFM of " + std::to_string(width) + " x " + std::to_string(height) +
                               " pixels is too large");

  const uint64_t expected = width * height * uint64_t(channels) * 4u;
  const uint64_t available = bytes.size() - cursor.dataStart();
  if (available != expected)
    throw InputError(name, "PFM of " + std::to_string(width) + " x " + std::to_string(height) +
                               " needs " + std::to_string(expected) + " bytes of pixels, found " +
                               std::to_string(available) +
                               (available < expected ? " (truncated)" : ""));

  const bool littleEndian = scale < 0.0;
  Image image{int(width), int(height)};
  const char* data = bytes.data() + cursor.dataStart();
  for (uint64_t row = 0; row < height; ++row) {
    const int y = int(height - 1 - row);  // stored bottom to top
    for (uint64_t x = 0; x < width; ++x) {
      Color& p = image.at(int(x), y);
      for (int c = 0; c < 3; ++c) {
        const int source = channels == 3 ? c : 0;
        p[c] = floatFromBytes(
            data + ((row * width + x) * uint64_t(channels) + uint64_t(source)) * 4, littleEndian);
      }
    }
  }
  return image;
}

}  // namespace rad
