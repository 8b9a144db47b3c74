// The JSON scene file, beside the test meshes and IES files it may refer to.
#include <radiosity/scene_loader.h>

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = rad::fuzz::writeInput(
      "small/fuzz.json", std::string_view(reinterpret_cast<const char*>(data), size));
  rad::fuzz::acceptingInputErrors([&] { rad::loadScene(path); });
  return 0;
}
