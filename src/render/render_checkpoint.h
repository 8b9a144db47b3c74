#pragma once
// A long path-traced render's finished tiles on disk, so that a render killed or interrupted
// part way goes on with the tiles it had not finished when run again, to the same picture bit
// for bit (each tile has its own random stream). Keyed by the scene's geometry, materials and
// lights, the camera and the settings; written atomically every half minute and when stopped,
// removed when the picture is done.

#include <radiosity/image.h>
#include <radiosity/path_tracer.h>
#include <radiosity/scene.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace rad {

struct RenderCheckpoint {
  std::vector<uint8_t> tileDone;  ///< 1 for each tile whose pixels are final
  Image image;                    ///< the finished tiles' pixels (others zero)
};

/// The checkpoint file of this render in settings.checkpointDir; empty when that is empty.
std::filesystem::path renderCheckpointFile(const Scene& scene, const Camera& camera,
                                           const PathTracerSettings& settings);

/// Writes the checkpoint atomically; returns a warning instead of throwing when it cannot.
std::string saveRenderCheckpoint(const std::filesystem::path& file, const RenderCheckpoint& state);

/// The checkpoint in `file` for `tiles` tiles of a width x height picture, if one fits;
/// `warning` says why a file that exists was not used.
std::optional<RenderCheckpoint> loadRenderCheckpoint(const std::filesystem::path& file,
                                                     size_t tiles, int width, int height,
                                                     std::string& warning);

}  // namespace rad
