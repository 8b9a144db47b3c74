#pragma once
// Solution files (.rad): a solved scene kept on disk, so that pictures, lit meshes and animations
// are made from it without solving again (PatchRadiosity::save and PatchModel::load, and the
// same for the voxel method). A file holds its format version, the method and the settings it
// was solved with, a key of the scene's geometry, materials and lights, the method's arrays (per
// light group when they were solved apart, so that a loaded solution rescales its groups too)
// and a checksum; it is written atomically. A file that is truncated, corrupt, of another
// version or of another scene is refused with an InputError that says which.

#include <radiosity/scene.h>

#include <string>

namespace rad {

/// What a solution file says of itself.
struct SolutionFileInfo {
  std::string method;       ///< the name of the registered method that wrote it
  SolverSettings settings;  ///< every setting the method was solved with, by name
};

/// Reads the file's method and settings, checking the whole file (version, checksum). Throws
/// InputError naming the file and why it cannot be used.
SolutionFileInfo readSolutionFileInfo(const std::string& path);

}  // namespace rad
