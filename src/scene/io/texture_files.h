#pragma once
// The textures a scene's files name, each decoded once however many materials use it. A texture
// that cannot be read is a warning naming it, and the material keeps its factor alone.

#include <radiosity/scene_builder.h>
#include <radiosity/texture.h>

#include <map>
#include <memory>
#include <span>
#include <string>

namespace rad {

class TextureFiles {
 public:
  explicit TextureFiles(SceneBuilder& builder) : builder_(builder) {}
  /// The texture in the file at `path`, or nullptr after a warning that names `material` and
  /// the scene file `source`.
  std::shared_ptr<const Texture> file(const std::string& path, const std::string& material,
                                      const std::string& source);
  /// The texture encoded in `bytes` (a glTF's embedded image), known as `key` to later calls.
  std::shared_ptr<const Texture> encoded(std::span<const uint8_t> bytes, const std::string& key,
                                         const std::string& material, const std::string& source);

 private:
  std::shared_ptr<const Texture> decodeOnce(const std::string& key, const std::string& material,
                                            const std::string& source, auto&& decode);
  SceneBuilder& builder_;
  std::map<std::string, std::shared_ptr<const Texture>> decoded_;
};

}  // namespace rad
