#pragma once
// Procedural textures for the generated scenes (no image files to ship): floor tiles and ashlar
// masonry, each tileable, with per-tile variation from a hash so that no two neighbours match,
// and a planar mapping that puts them on a generator's faces.

#include <radiosity/scene_builder.h>
#include <radiosity/texture.h>

#include <memory>

namespace rad {

/// Square tiles of two marble tones in a checker with grout lines: `tiles` x `tiles` tiles on
/// `size` x `size` texels. Linear colour, mean about 0.7.
std::shared_ptr<const Texture> makeFloorTiles(int size, int tiles);

/// Ashlar masonry: rows of blocks twice as long as high, every other row offset by half a
/// block, mortar joints, each block a little lighter or darker. `rows` rows on `size` x `size`
/// texels. Linear colour, mean about 0.7.
std::shared_ptr<const Texture> makeAshlar(int size, int rows);

/// Gives every vertex of `material`'s faces texture coordinates by projecting it onto the axis
/// plane closest to its face's plane (floors take x, z; walls their horizontal axis and -y, so
/// that rows stay level), `period` scene units to one repeat of the texture. The faces must not
/// share vertices with faces of other orientations.
void mapPlanar(SceneBuilder& builder, uint32_t material, float period);

/// The material's base colour texture at the factor that keeps its mean reflectance `rho`.
void applyTexture(Material& material, std::shared_ptr<const Texture> texture);

}  // namespace rad
