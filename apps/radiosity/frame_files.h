#pragma once
// The numbered files of an animation and the video made of them.

#include <string>

namespace rad::cli {

/// A frame file name pattern with one printf-style number field, %d or %0Nd ("%%" a percent
/// sign): frames/frame_%04d.png.
class FrameFiles {
 public:
  /// Throws InputError (naming -o) for a pattern without exactly one number field, or with an
  /// image format the writers do not know.
  explicit FrameFiles(std::string pattern);
  /// The file of frame `frame`.
  std::string name(int frame) const;
  /// Creates the frames' directory if it is missing.
  void createDirectory() const;
  bool png() const;
  /// The pattern as ffmpeg reads it (its own printf syntax: the same field).
  const std::string& pattern() const { return pattern_; }

 private:
  std::string pattern_, before_, after_;
  int width_ = 0;  ///< digits, zero-padded (0: as many as it takes)
};

/// Refuses, before any work, a video that cannot be made: a container other than .mp4, .mov or
/// .mkv, frames that are not PNG, or no ffmpeg on the PATH (InputError that says so).
void checkVideoOutput(const std::string& video, const FrameFiles& frames);
/// Encodes frames 0..count-1 at `fps` into `video` (H.264, yuv420p) with ffmpeg, atomically.
/// Throws std::runtime_error if ffmpeg fails.
void encodeVideo(const FrameFiles& frames, int count, double fps, const std::string& video);

}  // namespace rad::cli
