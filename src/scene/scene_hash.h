#pragma once
// What files computed from a scene hash of it, so that a file is used only for the scene it was
// computed for.

#include <radiosity/scene.h>

#include <span>

#include "core/binary_io.h"

namespace rad {

/// The geometry as the patch tables see it: positions, triangles, faces and sidedness.
void hashGeometry(Hasher& h, const Scene& scene);
/// The materials' reflectance and emission, by face.
void hashMaterials(Hasher& h, const Scene& scene);
/// Every field of the lights that changes their light (an IES light's profile by its file).
void hashLights(Hasher& h, std::span<const Light> lights);

}  // namespace rad
