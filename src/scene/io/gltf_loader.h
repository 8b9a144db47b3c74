#pragma once
// glTF 2.0 (.gltf with its buffers, or .glb) geometry into a SceneBuilder.

#include <radiosity/scene_builder.h>

#include <glm/mat4x4.hpp>
#include <string>

namespace rad {

/// Appends the triangles of the default scene of a glTF file to `builder`, node transforms
/// composed and then `transform` applied. Each mesh node becomes an object (node name, else mesh
/// name, else "node<i>"). Materials: baseColorFactor -> rho (1.0 is clamped to 0.999 with a
/// warning), emissiveFactor x KHR_materials_emissive_strength -> emission, doubleSided ->
/// twoSided; baseColorTexture and emissiveTexture (PNG or JPEG, embedded, in a GLB's buffer, or
/// in files beside the glTF named by relative, percent-encoded URIs) on TEXCOORD_0, with their
/// sampler's wrap modes and KHR_texture_transform; an image that cannot be read is a warning
/// naming its file and why, and its material keeps its factor. Only TRIANGLES primitives are
/// read (others: one warning).
/// Throws InputError naming the file (and JSON path) for unreadable, malformed or inconsistent
/// files.
void loadGltf(SceneBuilder& builder, const std::string& path, const glm::mat4& transform);

}  // namespace rad
