#pragma once
// Loading scenes: built-in names or files (.json scene files, .obj + .mtl, .gltf, .glb).

#include <radiosity/scene.h>

#include <string>
#include <vector>

namespace rad {

/// Loads a built-in scene ("cornell", "cornell-spot", "room:N", "atrium:N", "atrium-textured:N")
/// or a file, chosen by its extension. Throws InputError naming the file (and line or JSON path)
/// on any bad input.
/// Non-fatal problems (degenerate triangles dropped, ...) are left in Scene::warnings.
Scene loadScene(const std::string& nameOrPath);

/// Throws InputError if the scene has no emitting surface and no light: a render would be black.
void requireEmitters(const Scene& scene);

/// The built-in scene names, for help texts ("room:N" stands for a family).
std::vector<std::string> builtinSceneNames();

}  // namespace rad
