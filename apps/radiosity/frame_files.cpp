#include "frame_files.h"

#include <fmt/format.h>
#include <radiosity/atomic_file.h>
#include <radiosity/error.h>
#include <radiosity/image.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <vector>

extern char** environ;

namespace rad::cli {

namespace fs = std::filesystem;

namespace {

// The container ffmpeg writes for each video extension (named with -f, since the temporary file
// the video is written to first has no telling extension).
std::optional<std::string> containerOf(const std::string& video) {
  const std::string ext = fs::path(video).extension().string();
  if (ext == ".mp4") return "mp4";
  if (ext == ".mov") return "mov";
  if (ext == ".mkv") return "matroska";
  return std::nullopt;
}

std::optional<fs::path> findExecutable(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return std::nullopt;
  const std::string dirs = path;
  size_t start = 0;
  while (start <= dirs.size()) {
    const size_t end = std::min(dirs.find(':', start), dirs.size());
    const fs::path candidate = fs::path(dirs.substr(start, end - start)) / name;
    if (end > start && ::access(candidate.c_str(), X_OK) == 0) return candidate;
    start = end + 1;
  }
  return std::nullopt;
}

// Runs `args` (args[0] an executable path) and waits; its exit status, or -1 if it did not run.
int runProgram(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (::posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ) != 0) return -1;
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

FrameFiles::FrameFiles(std::string pattern) : pattern_(std::move(pattern)) {
  auto fail = [&](const std::string& why) { throw InputError("-o " + pattern_, why); };
  int fields = 0;
  std::string* part = &before_;
  for (size_t i = 0; i < pattern_.size(); ++i) {
    if (pattern_[i] != '%') {
      *part += pattern_[i];
      continue;
    }
    if (i + 1 < pattern_.size() && pattern_[i + 1] == '%') {
      *part += '%';
      ++i;
      continue;
    }
    size_t j = i + 1;
    const bool zeros = j < pattern_.size() && pattern_[j] == '0';
    int width = 0;
    while (j < pattern_.size() && std::isdigit(static_cast<unsigned char>(pattern_[j])))
      width = 10 * width + (pattern_[j++] - '0');
    if (j == pattern_.size() || pattern_[j] != 'd' || (width > 0 && !zeros) || width > 9)
      fail("a frame number field is %d or %0Nd (N up to 9), '%%' a percent sign");
    width_ = width;
    ++fields;
    part = &after_;
    i = j;
  }
  if (fields != 1) fail(fmt::format("needs one frame number field (%d or %0Nd), has {}", fields));
  if (!isSupportedImageFormat(name(0)))
    fail("unsupported image format (supported: .png, .exr, .pfm)");
}

std::string FrameFiles::name(int frame) const {
  return before_ + fmt::format("{:0{}d}", frame, width_) + after_;
}

void FrameFiles::createDirectory() const {
  const fs::path dir = fs::path(name(0)).parent_path();
  std::error_code ec;
  if (!dir.empty()) fs::create_directories(dir, ec);
  if (ec)
    throw InputError("-o " + pattern_,
                     fmt::format("cannot create {}: {}", dir.string(), ec.message()));
}

bool FrameFiles::png() const {
  return fs::path(name(0)).extension() == ".png";
}

void checkVideoOutput(const std::string& video, const FrameFiles& frames) {
  if (!containerOf(video))
    throw InputError("--video " + video, "expected a .mp4, .mov or .mkv file");
  if (!frames.png())
    throw InputError("--video " + video, "the frames must be PNG files to be encoded (-o ...png)");
  if (!findExecutable("ffmpeg"))
    throw InputError("--video " + video,
                     "ffmpeg is not installed (not on the PATH); install it (Debian: apt-get "
                     "install ffmpeg) or leave out --video: the frames are written either way");
}

void encodeVideo(const FrameFiles& frames, int count, double fps, const std::string& video) {
  const std::optional<fs::path> ffmpeg = findExecutable("ffmpeg");
  if (!ffmpeg) throw std::runtime_error("ffmpeg is no longer on the PATH");
  writeFileAtomically(video, [&](const fs::path& temporary) {
    // Odd sizes padded to even ones: H.264 in yuv420p halves the chroma both ways.
    const int status = runProgram({ffmpeg->string(),
                                   "-nostdin",
                                   "-loglevel",
                                   "error",
                                   "-y",
                                   "-framerate",
                                   fmt::format("{:g}", fps),
                                   "-start_number",
                                   "0",
                                   "-i",
                                   frames.pattern(),
                                   "-frames:v",
                                   std::to_string(count),
                                   "-vf",
                                   "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                   "-c:v",
                                   "libx264",
                                   "-pix_fmt",
                                   "yuv420p",
                                   "-f",
                                   *containerOf(video),
                                   temporary.string()});
    if (status != 0)
      throw std::runtime_error(fmt::format("ffmpeg failed (exit status {}) encoding {} into {}",
                                           status, frames.pattern(), video));
  });
}

}  // namespace rad::cli
