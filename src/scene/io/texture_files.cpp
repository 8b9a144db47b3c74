#include "scene/io/texture_files.h"

#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/message_text.h>

namespace rad {

std::shared_ptr<const Texture> TextureFiles::decodeOnce(const std::string& key,
                                                        const std::string& material,
                                                        const std::string& source, auto&& decode) {
  if (auto it = decoded_.find(key); it != decoded_.end()) return it->second;
  std::shared_ptr<const Texture> texture;
  try {
    texture = decode();
  } catch (const InputError& e) {
    builder_.warn(source, fmt::format("texture of material {} not used ({}): its factor alone "
                                      "colours it",
                                      quotedToken(material), e.what()));
  }
  decoded_[key] = texture;
  return texture;
}

std::shared_ptr<const Texture> TextureFiles::file(const std::string& path,
                                                  const std::string& material,
                                                  const std::string& source) {
  return decodeOnce(path, material, source, [&] { return Texture::load(path); });
}

std::shared_ptr<const Texture> TextureFiles::encoded(std::span<const uint8_t> bytes,
                                                     const std::string& key,
                                                     const std::string& material,
                                                     const std::string& source) {
  return decodeOnce(key, material, source, [&] { return Texture::decode(bytes, key); });
}

}  // namespace rad
