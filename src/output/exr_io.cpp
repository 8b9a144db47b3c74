#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>

#include <stdexcept>
#include <vector>

#include "output/image_formats.h"

namespace rad {

void writeExr(const std::filesystem::path& file, const Image& image, ExrPixelType type,
              const std::string& displayName) {
  const Imf::PixelType pixelType = type == ExrPixelType::Half ? Imf::HALF : Imf::FLOAT;
  const size_t count = image.pixels.size();
  // Planar buffers, one per channel; Imf reads them through strides.
  std::vector<float> floats;
  std::vector<half> halves;
  char* base[3];
  size_t elementSize = 0;
  if (pixelType == Imf::FLOAT) {
    floats.resize(3 * count);
    for (size_t i = 0; i < count; ++i)
      for (int c = 0; c < 3; ++c) floats[size_t(c) * count + i] = image.pixels[i][c];
    for (int c = 0; c < 3; ++c)
      base[c] = reinterpret_cast<char*>(floats.data() + size_t(c) * count);
    elementSize = sizeof(float);
  } else {
    halves.resize(3 * count);
    for (size_t i = 0; i < count; ++i)
      for (int c = 0; c < 3; ++c) halves[size_t(c) * count + i] = half(image.pixels[i][c]);
    for (int c = 0; c < 3; ++c)
      base[c] = reinterpret_cast<char*>(halves.data() + size_t(c) * count);
    elementSize = sizeof(half);
  }

  try {
    Imf::Header header(image.width, image.height);
    const char* names[3] = {"R", "G", "B"};
    Imf::FrameBuffer frame;
    for (int c = 0; c < 3; ++c) {
      header.channels().insert(names[c], Imf::Channel(pixelType));
      frame.insert(names[c],
                   Imf::Slice(pixelType, base[c], elementSize, elementSize * size_t(image.width)));
    }
    Imf::OutputFile out(file.c_str(), header);
    out.setFrameBuffer(frame);
    out.writePixels(image.height);
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot write '" + displayName + "': " + e.what());
  }
}

}  // namespace rad
