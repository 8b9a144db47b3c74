// A binary glTF (GLB): header, JSON chunk, BIN chunk.
#include <radiosity/scene_loader.h>

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = rad::fuzz::writeInput(
      "small/fuzz.glb", std::string_view(reinterpret_cast<const char*>(data), size));
  rad::fuzz::acceptingInputErrors([&] { rad::loadScene(path); });
  return 0;
}
