// OBJ with its MTL library: the input is the OBJ text, optionally followed by a line "%%MTL"
// and the text of fuzz.mtl (which the OBJ may name in its mtllib, or name small.mtl).
#include <radiosity/scene_loader.h>

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  constexpr std::string_view kSeparator = "\n%%MTL\n";
  const size_t split = input.find(kSeparator);
  rad::fuzz::writeInput("small/fuzz.mtl", split == std::string_view::npos
                                              ? std::string_view()
                                              : input.substr(split + kSeparator.size()));
  const std::string obj = rad::fuzz::writeInput("small/fuzz.obj", input.substr(0, split));
  rad::fuzz::acceptingInputErrors([&] { rad::loadScene(obj); });
  return 0;
}
