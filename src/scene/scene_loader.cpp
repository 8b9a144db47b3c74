// loadScene: built-in names first, then files by extension.

#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/scene_builder.h>
#include <radiosity/scene_loader.h>

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "scene/builtin/builtin_scenes.h"
#include "scene/io/gltf_loader.h"
#include "scene/io/obj_loader.h"
#include "scene/io/scene_json.h"

namespace rad {

namespace {

// N of a built-in "family:N" name.
int parseDetail(const std::string& name, const std::string& family) {
  const std::string digits = name.substr(family.size() + 1);
  int n = 0;
  auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
  if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size() || n < 1)
    throw InputError(name, fmt::format("'{}' is not a valid N for {}:N (expected an integer >= 1)",
                                       digits, family));
  return n;
}

}  // namespace

Scene loadScene(const std::string& nameOrPath) {
  if (nameOrPath == "cornell") return makeCornellBox(false);
  if (nameOrPath == "cornell-spot") return makeCornellBox(true);
  if (nameOrPath.rfind("room:", 0) == 0) return makeRoom(parseDetail(nameOrPath, "room"));
  if (nameOrPath.rfind("atrium:", 0) == 0) return makeAtrium(parseDetail(nameOrPath, "atrium"));
  if (nameOrPath.rfind("atrium-textured:", 0) == 0)
    return makeAtrium(parseDetail(nameOrPath, "atrium-textured"), true);

  std::error_code error;
  if (std::filesystem::is_directory(nameOrPath, error))
    throw InputError(
        nameOrPath,
        "is a directory, not a scene file (.json, .obj, .gltf, .glb) or "
        "a built-in scene (cornell, cornell-spot, room:N, atrium:N, atrium-textured:N)");
  std::string ext = std::filesystem::path(nameOrPath).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  const bool known = ext == ".json" || ext == ".obj" || ext == ".gltf" || ext == ".glb";
  if (!known) {
    if (ext.empty() && !std::filesystem::exists(nameOrPath))
      throw InputError(nameOrPath,
                       "cannot open: no such file and not a built-in scene (cornell, "
                       "cornell-spot, room:N, atrium:N, atrium-textured:N)");
    throw InputError(nameOrPath, fmt::format("unsupported scene extension '{}' (supported: .json, "
                                             ".obj, .gltf, .glb, or a built-in name)",
                                             ext));
  }
  if (!std::ifstream(nameOrPath, std::ios::binary))
    throw InputError(nameOrPath, "cannot open the scene file (missing or unreadable)");
  if (ext == ".json") return loadSceneJson(nameOrPath);
  SceneBuilder builder(nameOrPath);
  if (ext == ".obj") {
    loadObj(builder, nameOrPath, glm::mat4(1.0f));
  } else {
    loadGltf(builder, nameOrPath, glm::mat4(1.0f));
    builder.scene().unit = *lengthUnitNamed("m");  // glTF's, by its specification
  }
  return builder.build();
}

void requireEmitters(const Scene& scene) {
  if (!scene.hasEmitters())
    throw InputError(scene.name, "no emitting surface and no light: the render would be black");
}

std::vector<std::string> builtinSceneNames() {
  return {"cornell", "cornell-spot", "room:N", "atrium:N", "atrium-textured:N"};
}

}  // namespace rad
