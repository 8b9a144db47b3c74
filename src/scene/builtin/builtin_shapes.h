#pragma once
// Shapes the built-in scenes are made of, added to a SceneBuilder as planar faces.

#include <radiosity/scene_builder.h>

namespace rad {

enum class BoxSide { Outside, Inside };

/// An axis-aligned box as 6 quads, fronts facing out (furniture) or in (a room's shell).
/// `bottom` false leaves out the face that rests on the floor (-y).
void addBox(SceneBuilder& b, Vec3 lo, Vec3 hi, uint32_t material, uint32_t object, BoxSide side,
            bool bottom = true);

/// One planar quad (corners counter-clockwise about its front).
void addQuad(SceneBuilder& b, Vec3 a, Vec3 c1, Vec3 c2, Vec3 c3, uint32_t material,
             uint32_t object);

}  // namespace rad
