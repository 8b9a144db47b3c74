#pragma once
// The scene file's "sensors": points and calculation grids where the light is measured.

#include <radiosity/scene.h>

#include <vector>

#include "scene/io/json_reader.h"

namespace rad {

/// Reads the "sensors" array at /sensors: entries {"name", "position", "normal"} (a point) or
/// {"name", "grid": {"origin", "u", "v", "nu", "nv"}, "normal"} (nu x nv points at the centres
/// of the cells of the parallelogram origin + s u + t v, s and t in [0, 1], as EN 12464-1 lays
/// its calculation grids; the normal defaults to u x v's way). Names default to "sensor<i>" and
/// must differ.
std::vector<SensorSet> readSensors(const JsonReader& r, const Json& list);

}  // namespace rad
