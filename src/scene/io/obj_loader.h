#pragma once
// Wavefront OBJ + MTL geometry into a SceneBuilder.

#include <radiosity/scene_builder.h>

#include <glm/mat4x4.hpp>
#include <string>

namespace rad {

/// Appends the polygons of an OBJ file (and the materials of its MTL libraries) to `builder`.
/// Objects come from `o`/`g` names (an unnamed part takes the file stem); Kd -> rho, Ke ->
/// emission (radiance); faces without a material get a grey rho 0.5 (one warning). `transform`
/// maps file positions to scene positions (a mirroring transform keeps faces' fronts by
/// reversing their winding). Throws InputError naming "file.obj:LINE" or "file.mtl:LINE" for
/// malformed statements, indices out of range, non-finite numbers, rho outside [0, 1), and
/// "cannot open" for a missing OBJ or MTL file.
void loadObj(SceneBuilder& builder, const std::string& path, const glm::mat4& transform);

}  // namespace rad
