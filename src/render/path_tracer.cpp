// renderPathTraced: the reference image, pixel tiles in parallel, each tile with its own random
// stream so the image does not depend on the thread count.
#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/path_tracer.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <mutex>
#include <optional>

#include "core/checksummed_file.h"
#include "core/process_collectives.h"
#include "core/progress_ticker.h"
#include "geometry/sampling.h"
#include "render/camera_rays.h"
#include "render/path_integrator.h"
#include "render/path_tracer_settings.h"
#include "render/render_checkpoint.h"

namespace rad {

namespace {

constexpr int kTileSize = 16;

// Samples between two questions to the progress callback: at a million samples a pixel takes
// seconds, and Ctrl-C must stop the render within one.
constexpr int kSamplesBetweenPolls = 1024;

// Renders one tile; false if it was stopped before its last pixel.
bool renderTile(const PathIntegrator& integrator, const PinholeCamera& camera,
                const PathTracerSettings& settings, int tile, int tilesX, Image& image,
                ProgressTicker& ticker) {
  Rng rng(settings.seed, uint64_t(tile));
  const int x0 = (tile % tilesX) * kTileSize, y0 = (tile / tilesX) * kTileSize;
  const int x1 = std::min(x0 + kTileSize, image.width);
  const int y1 = std::min(y0 + kTileSize, image.height);
  const float weight = 1.0f / float(settings.samplesPerPixel);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      Color sum(0.0f);
      for (int s = 0; s < settings.samplesPerPixel; ++s) {
        if (s % kSamplesBetweenPolls == kSamplesBetweenPolls - 1 && ticker.pollCancelled())
          return false;
        const Vec2 offset = uniformSquare(rng);
        const Ray ray = camera.ray(x, y, offset);
        sum += settings.irradiance ? integrator.irradianceSeen(ray, rng)
                                   : integrator.radiance(ray, rng);
      }
      image.at(x, y) = sum * weight;
      ticker.tick();
    }
  return true;
}

// The tiles finished so far and their pixels, written to the render's checkpoint file.
class TileCheckpoint {
 public:
  TileCheckpoint(std::filesystem::path file, int tiles, int tilesX, const Image& image)
      : file_(std::move(file)), tilesX_(tilesX), image_(image), done_(size_t(tiles)) {}

  /// Takes the tiles of a checkpoint of this render, if there is one; their count.
  size_t resume(Image& image, std::vector<std::string>& warnings) {
    if (file_.empty()) return 0;
    std::string warning;
    std::optional<RenderCheckpoint> c =
        loadRenderCheckpoint(file_, done_.size(), image.width, image.height, warning);
    if (!warning.empty()) warnings.push_back(warning);
    if (!c) return 0;
    image = std::move(c->image);
    size_t count = 0;
    for (size_t t = 0; t < done_.size(); ++t) {
      done_[t] = c->tileDone[t] != 0;
      count += done_[t];
    }
    return count;
  }
  bool done(int tile) const { return done_[size_t(tile)].load(std::memory_order_acquire); }
  /// Marks a tile finished; writes the checkpoint when the last one is old enough
  /// (checkpointIntervalSeconds).
  void finished(int tile) {
    done_[size_t(tile)].store(1, std::memory_order_release);
    if (file_.empty() || since_.seconds() < interval_) return;
    std::unique_lock lock(writing_, std::try_to_lock);
    if (!lock.owns_lock() || since_.seconds() < interval_) return;
    write();
    since_ = {};
  }
  /// Writes the finished tiles; true when a checkpoint is there to go on from.
  bool write() {
    if (file_.empty()) return false;
    RenderCheckpoint c;
    c.image = Image(image_.width, image_.height);
    c.tileDone.resize(done_.size());
    for (int t = 0; t < int(done_.size()); ++t) {
      if (!(c.tileDone[size_t(t)] = done(t))) continue;
      const int x0 = (t % tilesX_) * kTileSize, y0 = (t / tilesX_) * kTileSize;
      for (int y = y0; y < std::min(y0 + kTileSize, image_.height); ++y)
        for (int x = x0; x < std::min(x0 + kTileSize, image_.width); ++x)
          c.image.at(x, y) = image_.at(x, y);
    }
    warning_ = saveRenderCheckpoint(file_, c);
    return warning_.empty();
  }
  size_t doneCount() const {
    size_t count = 0;
    for (int t = 0; t < int(done_.size()); ++t) count += done(t);
    return count;
  }
  void remove() const {
    std::error_code ignored;
    if (!file_.empty()) std::filesystem::remove(file_, ignored);
  }
  const std::filesystem::path& file() const { return file_; }
  const std::string& warning() const { return warning_; }

 private:
  struct Since {
    double seconds() const {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  };
  std::filesystem::path file_;
  int tilesX_;
  const Image& image_;
  std::vector<std::atomic<uint8_t>> done_;
  std::mutex writing_;
  Since since_;
  const double interval_ = checkpointIntervalSeconds();
  std::string warning_;
};

}  // namespace

PathTracedImage renderPathTraced(const Scene& scene, const Camera& camera,
                                 const PathTracerSettings& settings,
                                 const ProgressCallback& progress) {
  validatePathTracerSettings(settings);
  return renderPathTraced(scene, RayCaster(scene), camera, settings, progress);
}

PathTracedImage renderPathTraced(const Scene& scene, const RayCaster& caster, const Camera& camera,
                                 const PathTracerSettings& settings,
                                 const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  validatePathTracerSettings(settings);
  const uint64_t raysBefore = caster.raysCast();
  const PinholeCamera pinhole(camera);
  const PathIntegrator integrator(scene, caster, settings.maxDepth);

  PathTracedImage result;
  result.image = Image(camera.width, camera.height);
  const int tilesX = (camera.width + kTileSize - 1) / kTileSize;
  const int tilesY = (camera.height + kTileSize - 1) / kTileSize;
  const ProcessShare& share = settings.processes;
  // A split render keeps no checkpoint: each process would keep its own tiles under one name.
  TileCheckpoint checkpoint(
      share.split() ? std::filesystem::path() : renderCheckpointFile(scene, camera, settings),
      tilesX * tilesY, tilesX, result.image);
  result.stats.resumedTiles = checkpoint.resume(result.image, result.stats.warnings);
  // Every count-th tile from the rank: the processes' shares of the picture interleave, so
  // that an expensive region is shared too.
  auto mine = [&](int tile) { return tile % share.count == share.rank; };
  ProgressTicker ticker(progress,
                        size_t(camera.width) * size_t(camera.height) / size_t(share.count));
  tbb::parallel_for(tbb::blocked_range<int>(0, tilesX * tilesY), [&](const auto& range) {
    for (int tile = range.begin(); tile != range.end(); ++tile) {
      if (ticker.cancelled()) return;
      if (!mine(tile) || checkpoint.done(tile)) continue;
      if (renderTile(integrator, pinhole, settings, tile, tilesX, result.image, ticker))
        checkpoint.finished(tile);
    }
  });
  if (ticker.cancelled()) {
    if (checkpoint.doneCount() == 0 || !checkpoint.write()) throw Cancelled();
    throw Cancelled(
        fmt::format("the {} of {} tiles finished are kept in {}: rendered again, it "
                    "renders only the rest",
                    checkpoint.doneCount(), tilesX * tilesY, checkpoint.file().string()));
  }
  if (!checkpoint.warning().empty()) result.stats.warnings.push_back(checkpoint.warning());
  checkpoint.remove();

  result.stats.rays = caster.raysCast() - raysBefore;
  // The processes' tiles added up (every pixel is one process's), and their rays.
  sumOverProcesses(share, result.image.pixels);
  result.stats.rays = sumOverProcesses(share, result.stats.rays);
  result.stats.paths =
      uint64_t(camera.width) * uint64_t(camera.height) * uint64_t(settings.samplesPerPixel);
  result.stats.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace rad
