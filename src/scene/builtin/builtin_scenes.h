#pragma once
// Scenes built in code, reachable by name from loadScene (see scene_loader.cpp).

#include <radiosity/scene.h>

namespace rad {

/// The Cornell box (Cornell University Program of Computer Graphics, "Cornell Box Data"), in
/// millimetres, geometry identical to tests/data/scene/cornell/cornell_box.obj (docs/references.md
/// 2.4). With `spot`, the ceiling light is switched off and a spot light below it is aimed at the
/// floor.
Scene makeCornellBox(bool spot);

/// A procedural furnished room whose triangle count grows roughly linearly with n (>= 1;
/// InputError otherwise). Deterministic for a given n.
Scene makeRoom(int n);

/// A generated interior of columns, arches, railings and a vault lit by point and spot lights,
/// whose curved parts have detail n (>= 1; InputError otherwise): the kind of scene real
/// interiors are, for accuracy and scale tests; `textured`: its floor, walls and vault under
/// procedural textures. Deterministic.
Scene makeAtrium(int n, bool textured = false);

}  // namespace rad
