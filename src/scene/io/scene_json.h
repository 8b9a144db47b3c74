#pragma once
// The JSON scene file (docs/ARCHITECTURE.md "Scene file").

#include <radiosity/scene.h>

#include <string>

namespace rad {

/// Loads a .json scene file: its length unit, geometry files (relative to the scene file) with
/// optional transforms and materials, material overrides by name, lights, camera, dynamic objects
/// and solver settings.
///
/// "transform": {"translate": [x,y,z], "rotate_deg": [rx,ry,rz], "scale": s or [sx,sy,sz]}
/// applies scale, then rotation (about x, then y, then z; fixed axes, degrees), then
/// translation. Unknown keys, wrong types and out-of-range values throw InputError naming
/// "file: /json/path"; malformed JSON names "file:line:column".
Scene loadSceneJson(const std::string& path);

}  // namespace rad
