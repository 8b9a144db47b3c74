#include "scene/io/exr_reader.h"

#include <Imath/ImathBox.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <radiosity/error.h>

#include <string>

namespace rad {

namespace {

// A guard against headers that claim absurd sizes before we allocate for them.
constexpr int64_t kMaxPixels = int64_t(1) << 30;
static_assert(sizeof(Color) == 3 * sizeof(float), "readExr writes R, G, B floats in place");

}  // namespace

Image readExr(const std::filesystem::path& file) {
  const std::string name = file.string();
  try {
    Imf::InputFile in(file.c_str());
    const Imath::Box2i window = in.header().dataWindow();
    const int64_t width = int64_t(window.max.x) - window.min.x + 1;
    const int64_t height = int64_t(window.max.y) - window.min.y + 1;
    if (width <= 0 || height <= 0 || width * height > kMaxPixels)
      throw InputError(name, "EXR data window of " + std::to_string(width) + " x " +
                                 std::to_string(height) + " pixels is not supported");

    const Imf::ChannelList& channels = in.header().channels();
    const bool hasRgb =
        channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B");
    if (!hasRgb && !channels.findChannel("Y"))
      throw InputError(name, "EXR has neither R, G, B nor Y channels");

    Image image{int(width), int(height)};
    // Pixels are interleaved floats; the frame buffer's origin is shifted so that the data
    // window's corner lands on pixel (0, 0). Imf converts half and uint to float on read.
    char* origin = reinterpret_cast<char*>(image.pixels.data()) -
                   (int64_t(window.min.x) + int64_t(window.min.y) * width) * int64_t(sizeof(Color));
    const size_t xStride = sizeof(Color), yStride = sizeof(Color) * size_t(width);
    Imf::FrameBuffer frame;
    if (hasRgb) {
      frame.insert("R", Imf::Slice(Imf::FLOAT, origin + 0 * sizeof(float), xStride, yStride));
      frame.insert("G", Imf::Slice(Imf::FLOAT, origin + 1 * sizeof(float), xStride, yStride));
      frame.insert("B", Imf::Slice(Imf::FLOAT, origin + 2 * sizeof(float), xStride, yStride));
    } else {
      frame.insert("Y", Imf::Slice(Imf::FLOAT, origin, xStride, yStride));
    }
    in.setFrameBuffer(frame);
    in.readPixels(window.min.y, window.max.y);
    if (!hasRgb)
      for (Color& p : image.pixels) p = Color(p.r);
    return image;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    // OpenEXR reports truncation and corruption as Iex exceptions; to the user it is bad input.
    throw InputError(name, std::string("not a readable EXR image: ") + e.what());
  }
}

}  // namespace rad
