#include "voxel/voxel_solver.h"

#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/process_memory.h>
#include <radiosity/ray_caster.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>
#include <glm/gtc/constants.hpp>
#include <map>
#include <memory>

#include "core/process_collectives.h"
#include "core/progress_ticker.h"
#include "core/rng.h"
#include "core/vector_memory.h"
#include "geometry/sampling.h"
#include "lighting/direct_lighting.h"
#include "voxel/direction_set.h"
#include "voxel/exact_color_sum.h"
#include "voxel/half_float.h"
#include "voxel/voxel_checkpoint.h"
#include "voxel/voxelizer.h"

namespace rad {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The pieces at `count` evenly spaced places along a side's area, its pieces end to end
// (systematic sampling: each piece takes about its share of the places): f(place, piece) for
// each in order until it returns false.
template <typename F>
void forEvenlySpacedPieces(std::span<const SidePiece> pieces, double area, int count, F&& f) {
  size_t i = 0;
  double end = pieces[0].area;
  for (int s = 0; s < count; ++s) {
    const double at = (double(s) + 0.5) / double(count) * area;
    while (at > end && i + 1 < pieces.size()) end += pieces[++i].area;
    if (!f(s, pieces[i])) return;
  }
}

// A side's irradiance from the skies: `samples` cosine-weighted rays, each from the centroid of
// the next of as many evenly spaced pieces along its normal, in the next stratum of the disk the
// directions lift from (pieces and directions stratified together, as the emitters' samples).
Vec3d skyOnSide(const DirectLighting& direct, std::span<const Light> skies,
                std::span<const SidePiece> pieces, double area, int samples, Rng& rng) {
  Vec3d sum(0.0);
  forEvenlySpacedPieces(pieces, area, samples, [&](int s, const SidePiece& p) {
    const Vec2 u = stratifiedSample(s, samples, rng);
    for (const Light& sky : skies) sum += Vec3d(direct.skySample(sky, p.centroid, p.normal, u));
    return true;
  });
  return sum / double(samples);
}

// Direct irradiance at every entry: the mean over the pieces of surface it stands for
// (forEachSidesPieces), each lit at its centroid along its own normal. The analytic lights are
// exact (one shadow ray each) at every piece, or at kLightPieces evenly spaced by area where it
// has more; the emitters' light is the mean of `directSamples` area samples, each from the
// centroid of the next of as many evenly spaced pieces, and a sky's of as many rays (skyOnSide).
// Lit from the side's centroid, along its mean normal, small round objects were dark: the centroid
// of a door knob's side lay inside the knob, and one normal stood for a curtain rod's fan of facets
// (living_room_bare at 100k voxels: the knob -17%, the rod -6% of the path tracer's direct light;
// now -7% and +1%, the knob's long facets lit at their centroids). Points spread over the pieces
// came nearer the truth on the knob, but near an emitter's edge (a window frame against its glass,
// a wall against a lamp) their samples' 1 / d^2 made sides far noisier. Throws Cancelled when
// `progress` asks, within a fraction of a second even at thousands of samples a side.
std::vector<Color> directIrradiance(const Scene& scene, const VoxelGrid& grid,
                                    const RayCaster& caster, std::span<const Light> lights,
                                    const VoxelSolverSettings& settings, uint64_t& rays,
                                    const ProgressCallback& progress) {
  constexpr int kSamplesBetweenPolls = 256;
  constexpr int kLightPieces = 64;
  const uint64_t raysBefore = caster.raysCast();
  std::vector<Light> analytic, skies;
  for (const Light& light : lights)
    (light.type == LightType::Sky ? skies : analytic).push_back(light);
  const DirectLighting direct(scene, caster, analytic, settings.emissionScales);
  std::vector<Color> h(grid.entryCount(), Color(0.0f));
  // Split among processes, each shoots a block of the sides; their sum is every side's.
  const auto [begin, end] = settings.processes.block(grid.entryCount());
  ProgressTicker ticker(progress, end - begin);
  forEachSidesPieces(scene, grid, begin, end, [&](size_t e, std::span<const SidePiece> pieces) {
    double area = 0.0;
    for (const SidePiece& p : pieces) area += p.area;
    Vec3d sum(0.0);
    Rng rng(settings.seed, e);
    if (direct.hasEmitters()) {
      bool cancelled = false;
      forEvenlySpacedPieces(pieces, area, settings.directSamples, [&](int s, const SidePiece& p) {
        if (s % kSamplesBetweenPolls == kSamplesBetweenPolls - 1 && ticker.pollCancelled())
          return !(cancelled = true);
        sum += Vec3d(direct.sampleEmitters(p.centroid, p.normal, rng));
        return true;
      });
      if (cancelled) return false;
      sum /= double(settings.directSamples);
    }
    if (direct.hasLights()) {
      if (pieces.size() <= size_t(kLightPieces))
        for (const SidePiece& p : pieces)
          sum += p.area / area * Vec3d(direct.fromLights(p.centroid, p.normal));
      else
        forEvenlySpacedPieces(pieces, area, kLightPieces, [&](int, const SidePiece& p) {
          sum += Vec3d(direct.fromLights(p.centroid, p.normal)) / double(kLightPieces);
          return true;
        });
    }
    if (!skies.empty()) sum += skyOnSide(direct, skies, pieces, area, settings.directSamples, rng);
    h[e] = Color(sum);
    ticker.tick();
    return !ticker.cancelled();
  });
  ticker.throwIfCancelled();
  rays = caster.raysCast() - raysBefore;
  sumOverProcesses(settings.processes, h);
  return h;
}

// Sum of cos * w over the directions each entry faces: what a fully lit side gathers from a
// surface of unit radiosity, which the normalization divides by. Depends on the normal only, so
// it is computed once per distinct normal (a room's walls share a handful). Kept as w - 1 in half
// floats (2 bytes a side): w lies near 1, and the half float's 11 bits of w - 1 leave an error
// below 1e-4 w even for spheres of a few directions (|w - 1| ~ 0.2), below 1e-5 at R = 38.
std::vector<uint16_t> facingWeights(const VoxelGrid& grid, const DirectionSet& directions) {
  std::map<std::array<int16_t, 3>, uint32_t> index;
  std::vector<Vec3> distinct;
  std::vector<uint32_t> normalOf(grid.entryCount());
  for (size_t e = 0; e < grid.entryCount(); ++e) {
    const auto [it, inserted] =
        index.try_emplace(grid.orientation[e].normal.v, uint32_t(distinct.size()));
    if (inserted) distinct.push_back(grid.unitNormal(e));
    normalOf[e] = it->second;
  }
  std::vector<float> weightOf(distinct.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, distinct.size(), 16), [&](const auto& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      double sum = 0.0;
      for (size_t d = 0; d < directions.size(); ++d)
        sum += std::max(0.0, glm::dot(Vec3d(distinct[i]), directions[d].unit)) *
               directions[d].solidAngle;
      weightOf[i] = float(sum / glm::pi<double>());
    }
  });
  std::vector<uint16_t> weights(grid.entryCount());
  for (size_t e = 0; e < weights.size(); ++e) weights[e] = toHalf(weightOf[normalOf[e]] - 1.0f);
  return weights;
}

// The line shift of pair k in an iteration: fixed by the seed, so results are reproducible.
LineOffset lineOffset(const DiscreteDirection& d, uint64_t seed, int iteration, size_t k) {
  Rng rng(seed ^ (uint64_t(iteration) << 32), k);
  const int64_t a = std::max({std::abs(d.step.x), std::abs(d.step.y), std::abs(d.step.z)});
  return {int64_t(rng.next() % uint64_t(a)), int64_t(rng.next() % uint64_t(a))};
}

// The bounces after the last iteration, summed, as a multiple of the last one, per channel.
// Each bounce is the one before reflected once more, and after a few their power falls by a
// steady ratio r (the fraction of light the scene's surfaces send on, seen from where light now
// is): the rest is the last bounce times r + r^2 + ... = r / (1 - r), spread as it was (the
// shape the bounces settle into). 0 when there is no ratio yet or the powers do not fall.
// Per channel, since surfaces send on different shares of red, green and blue: one ratio of the
// luminance's powers is a blend that drifts towards the channel that lasts longest (on room:4,
// 0.55 after two iterations, 0.61 after six, 0.63 after forty), and left red 0.4% dark and blue
// 0.4% bright there after six iterations.
Color tailFactor(const std::vector<Vec3d>& bouncePower) {
  const size_t k = bouncePower.size();
  Color factor(0.0f);
  if (k < 2) return factor;
  for (int c = 0; c < 3; ++c) {
    const double before = bouncePower[k - 2][c], last = bouncePower[k - 1][c];
    const double r = before > 0.0 ? last / before : 0.0;
    if (r > 0.0 && r < 1.0) factor[c] = float(r / (1.0 - r));
  }
  return factor;
}

double luminance(const Vec3d& power) {
  return double(rad::luminance(Color(power)));
}

// The sides' reflectance, area- and luminance-weighted: the share of light a closed room's
// bounces send on, which the residuals fall by until they show their own ratio.
double meanReflectance(const VoxelGrid& grid) {
  double reflected = 0.0, area = 0.0;
  for (size_t e = 0; e < grid.entryCount(); ++e) {
    reflected += double(grid.areaOf(e)) * rad::luminance(grid.materialOf(e).rho);
    area += grid.areaOf(e);
  }
  return area > 0.0 ? reflected / area : 0.0;
}

// The iterations a solve is expected to take in all, for its progress: every one without a
// tolerance; else until the residual, falling by the ratio of the last two (before there are
// two, by `meanRho`; the first residual is about that share of the light put in), passes the
// tolerance; at most the cap.
int expectedIterations(const VoxelSolverSettings& s, std::span<const double> residuals,
                       double meanRho) {
  if (!(s.tolerance > 0.0)) return s.iterations;
  const size_t done = residuals.size();
  const double last = done > 0 ? residuals.back() : 1.0;
  if (last < s.tolerance) return int(done);
  const double ratio =
      done >= 2 && residuals[done - 2] > 0.0 ? last / residuals[done - 2] : meanRho;
  if (!(ratio > 0.0 && ratio < 1.0)) return s.iterations;
  const double more = std::max(1.0, std::ceil(std::log(s.tolerance / last) / std::log(ratio)));
  return int(std::min(double(done) + more, double(s.iterations)));
}

// The directions of the first sweep (R) and of the later ones: the same set, or a coarser one
// when asked (their light, the second bounce on, is smoother).
struct SweepDirections {
  explicit SweepDirections(const VoxelSolverSettings& settings) : first(settings.sphereRadius) {
    const int later = settings.laterSphereRadius;
    if (later > 0 && later != settings.sphereRadius)
      coarser = std::make_unique<const DirectionSet>(later);
  }
  const DirectionSet& later() const { return coarser ? *coarser : first; }

  DirectionSet first;
  /// Null when the later bounces use the first set. (A std::optional here made GCC 12 warn,
  /// wrongly, that its vectors may be used uninitialized, in the sanitizers' build.)
  std::unique_ptr<const DirectionSet> coarser;
};

// The direction pairs of an iteration go in fixed blocks, whatever the number of processes:
// each block's light is gathered in floats, then added exactly (ExactColorSum), so one process
// and any split of the blocks give the same bounce, bit for bit. A block is 8 pairs at least
// (its exact addition, a pass over the sides, then costs about a twentieth of its sweeps), and
// their count the largest of these that allows: counts that share out evenly among many
// process counts (240: 2, 3, 4, 5, 6, 8, 10, 12, 15 or 16 processes; 64, to within 1/4 block).
constexpr size_t kPairsPerBlock = 8;
constexpr std::array<size_t, 10> kBlockCounts = {240, 120, 60, 48, 24, 12, 6, 4, 2, 1};

size_t pairBlocks(size_t pairs) {
  for (size_t count : kBlockCounts)
    if (count * kPairsPerBlock <= pairs) return count;
  return 1;
}

// The pairs [first, last) of block b of `blocks` (1 at least).
std::pair<size_t, size_t> blockPairs(size_t pairs, size_t blocks, size_t b) {
  return {pairs * b / blocks, pairs * (b + 1) / blocks};
}

// The counts' unit, 2^-58 of the power of two above the largest light sent: a side gathers at
// most that light times the sum of cos x solid angle / pi over its hemisphere's directions
// (about 1; above 1 by the sphere's error), so every sum stays below 2^60 counts, with room to
// spare below the 2^62 kept, and a side that gathers a millionth of the largest light is
// counted in units of 3e-12 of its value.
float exactUnit(const DiscreteLineSweep::Source& source) {
  uint16_t largest = 0;  // half floats of one sign order as their bits
  for (const DiscreteLineSweep::SentLight& side : source.sides)
    largest = std::max({largest, side.radiosity[0], side.radiosity[1], side.radiosity[2]});
  int exponent = 0;
  std::frexp(fromHalf(largest) * source.scale, &exponent);
  return std::ldexp(1.0f, exponent - 58);
}

// One iteration, one bounce: the blocks of direction pairs in turn, each pair swept by all
// threads (over bands of its lines), so that every side's float sum runs over a block's pairs in
// the same order for any thread count. Split among processes, each sweeps its share of the
// blocks (the same ones every iteration: a pair's lines shift by its own seed, whoever sweeps
// it), and the exact sums are added.
void gatherAllDirections(const DirectionSet& directions, DiscreteLineSweep& sweep,
                         std::vector<Color>& gathered, const DiscreteLineSweep::Source& source,
                         const VoxelSolverSettings& settings, int iteration,
                         ProgressTicker& ticker) {
  const size_t pairs = directions.pairCount();
  const size_t blocks = pairBlocks(pairs);
  ExactColorSum sum(gathered.size(), exactUnit(source));
  const auto [firstBlock, lastBlock] = settings.processes.block(blocks);
  for (size_t b = firstBlock; b < lastBlock; ++b) {
    std::fill(gathered.begin(), gathered.end(), Color(0.0f));
    const auto [firstPair, lastPair] = blockPairs(pairs, blocks, b);
    for (size_t k = firstPair; k < lastPair; ++k) {
      ticker.throwIfCancelled();
      const DiscreteDirection& d = directions.pairFirst(k);
      const LineOffset offset =
          settings.jitterLines ? lineOffset(d, settings.seed, iteration, k) : LineOffset{};
      sweep.sweepPair(d, source, gathered, offset);
      ticker.tick();
    }
    sum.add(gathered);
  }
  sum.sumOverProcesses(settings.processes);
  sum.store(gathered);
}

// A colour in three 24-bit floats, 9 bytes: a float rounded to its 15 high bits of mantissa
// (to 2^-16 of its value), its sign and exponent kept, so that any scene's units fit; the bytes
// are the float's high three on this little-endian target. H so far is kept so: it changes only
// between the sweeps, a bounce at a time, and six bounces' roundings leave it within 1e-4 of its
// float sum (typically 2e-5).
class Float24Color {
 public:
  Float24Color() = default;
  explicit Float24Color(const Color& c) {
    for (int k = 0; k < 3; ++k) {
      uint32_t bits;
      std::memcpy(&bits, &c[k], sizeof bits);
      // Rounded to nearest: a carry into the exponent is the next representable value.
      bits = (bits + 0x80u) >> 8;
      std::memcpy(&bytes_[size_t(3 * k)], &bits, 3);
    }
  }
  Color value() const {
    Color c;
    for (int k = 0; k < 3; ++k) {
      uint32_t bits = 0;
      std::memcpy(&bits, &bytes_[size_t(3 * k)], 3);
      bits <<= 8;
      std::memcpy(&c[k], &bits, sizeof bits);
    }
    return c;
  }

 private:
  std::array<uint8_t, 9> bytes_{};
};
static_assert(sizeof(Float24Color) == 9);

// The line table the sweeps need, over all their directions: as large as the widest
// direction's (reserved at once, so that it never grows by reallocation, which would hold two
// tables).
size_t widestLineTable(const VoxelGrid& grid, const SweepDirections& directions) {
  std::vector<IVec3> steps;
  auto add = [&](const DirectionSet& set) {
    for (size_t k = 0; k < set.pairCount(); ++k) steps.push_back(set.pairFirst(k).step);
  };
  add(directions.first);
  if (directions.coarser) add(*directions.coarser);
  return maxLineCount(grid, steps);
}

uint64_t solveBytes(const VoxelGrid& grid, size_t lines, const VoxelSolverSettings& settings) {
  return grid.entryCount() * voxelSolverBytesPerSide(settings) +
         DiscreteLineSweep::workingBytesFor(grid, lines);
}

// A grid whose solve does not fit is an input error before the first shot, not a kill by the
// OOM killer an hour in.
void checkMemory(const VoxelGrid& grid, size_t lines, const VoxelSolverSettings& settings) {
  requireMemory(double(solveBytes(grid, lines, settings)), "voxel grid",
                fmt::format("{} voxel sides (to sweep)", grid.entryCount()),
                "use a larger voxel size or fewer voxels");
}

// The light of every side as the iterations go: H so far (the first shot's direct light, then
// one bounce more with every iteration) and the bounce the sweeps gather now. The sweeps carry
// one bounce at a time (Jacobi's iterations split by bounce, which gives the same sum): first
// what the emitters send, or, after a first shot, the direct light reflected; then the light of
// the bounce before, reflected. Each bounce is all positive, so its power is exactly how much B
// changes, free of the noise of the lines' shifts and of the half floats. H is kept in 24-bit
// floats (Float24Color, 9 bytes a side instead of 12); the bounce being gathered in floats.
class SideLight {
 public:
  SideLight(const VoxelGrid& grid, const VoxelSolverSettings& settings,
            const DirectionSet& directions, std::vector<Color> direct)
      : grid_(grid),
        firstShot_(settings.directFirstShot),
        normalize_(settings.normalize),
        emissionScales_(settings.emissionScales),
        irradiance_(direct.begin(), direct.end()),
        gathered_(grid.entryCount()) {
    normalizeFor(directions);
  }

  /// Makes the bounces gathered from now on normalized for the sweeps over `directions`.
  void normalizeFor(const DirectionSet& directions) {
    if (normalize_) weights_ = facingWeights(grid_, directions);
  }

  /// What side e sends in the next sweep (the first, or one after it).
  Color sends(size_t e, bool first) const {
    if (first) return firstShot_ ? rho(e) * irradiance(e) : emitted(e);
    return rho(e) * lastBounce(e);
  }
  /// Where the sweeps gather the next bounce (each iteration clears it first).
  std::vector<Color>& gathered() { return gathered_; }
  /// Adds the bounce just gathered to H; returns the power it adds to B and B's power then
  /// (area-weighted, per channel).
  std::pair<Vec3d, Vec3d> addBounce() {
    Vec3d added(0.0), total(0.0);
    for (size_t e = 0; e < irradiance_.size(); ++e) {
      const Color bounce = lastBounce(e);
      irradiance_[e] = Float24Color(irradiance(e) + bounce);
      added += power(e, rho(e) * bounce);
      total += power(e, radiosity(e));
    }
    return {added, total};
  }
  /// B's power now (area-weighted, per channel).
  Vec3d totalPower() const {
    Vec3d total(0.0);
    for (size_t e = 0; e < irradiance_.size(); ++e) total += power(e, radiosity(e));
    return total;
  }
  /// Adds the last bounce again, times `factor` per channel: the bounces after it (tailFactor).
  void addLastBounceTimes(const Color& factor) {
    for (size_t e = 0; e < irradiance_.size(); ++e)
      irradiance_[e] = Float24Color(irradiance(e) + factor * lastBounce(e));
  }
  /// Lets the last bounce go (no more sends, no tail): its memory goes before the results come.
  void releaseBounce() {
    releaseMemory(gathered_);
    releaseMemory(weights_);
  }
  std::vector<Color> radiosities() const {
    std::vector<Color> b(irradiance_.size());
    for (size_t e = 0; e < b.size(); ++e) b[e] = radiosity(e);
    return b;
  }
  std::vector<Color> irradiances() const {
    std::vector<Color> h(irradiance_.size());
    for (size_t e = 0; e < h.size(); ++e) h[e] = irradiance(e);
    return h;
  }

 private:
  Color emitted(size_t e) const {
    const VoxelSurface& s = grid_.surfaces[grid_.surface[e]];
    const Color e0 = glm::pi<float>() * s.material.emission;
    if (emissionScales_.empty() || s.emitter == VoxelSurface::kNoEmitter) return e0;
    return e0 * emissionScales_[s.emitter];
  }
  Color rho(size_t e) const { return grid_.materialOf(e).rho; }
  Color irradiance(size_t e) const { return irradiance_[e].value(); }
  Color radiosity(size_t e) const { return emitted(e) + rho(e) * irradiance(e); }
  Vec3d power(size_t e, const Color& c) const { return double(grid_.areaOf(e)) * Vec3d(c); }
  /// The light the last iteration's sweeps brought side e, normalized.
  Color lastBounce(size_t e) const {
    const float weight = weights_.empty() ? 1.0f : 1.0f + fromHalf(weights_[e]);
    return gathered_[e] / (weight > 0.0f ? weight : 1.0f);
  }

  const VoxelGrid& grid_;
  bool firstShot_, normalize_;
  std::span<const Color> emissionScales_;
  std::vector<Float24Color> irradiance_;
  std::vector<Color> gathered_;
  std::vector<uint16_t> weights_;  ///< per side, its facing weight w - 1 (facingWeights)
};

}  // namespace

uint64_t voxelSolverBytesPerSide(const VoxelSolverSettings& settings) {
  return sizeof(Color) +                                // the bounce being gathered
         ExactColorSum::kBytesPerColor +                // and its exact sum
         sizeof(Float24Color) +                         // irradiance so far
         sizeof(DiscreteLineSweep::SentLight) +         // light sent
         (settings.normalize ? sizeof(uint16_t) : 0) +  // normalization weights
         (settings.keepsDirect() ? sizeof(Color) : 0);  // the first shot, kept apart
}

uint64_t voxelSolveBytes(const VoxelGrid& grid, const VoxelSolverSettings& settings) {
  return solveBytes(grid, widestLineTable(grid, SweepDirections(settings)), settings);
}

namespace {

// The checkpoint of the solve's file to go on from, if it has one that fits; its numbers so far
// go into `solution`.
std::optional<VoxelCheckpoint> resumeFrom(const std::filesystem::path& file, size_t sides,
                                          VoxelSolution& solution) {
  if (file.empty()) return std::nullopt;
  std::string warning;
  std::optional<VoxelCheckpoint> c = loadVoxelCheckpoint(file, sides, warning);
  if (!warning.empty()) solution.warnings.push_back(warning);
  if (!c) return std::nullopt;
  solution.resumedIterations = c->iterationsDone;
  solution.residuals = c->residuals;
  solution.iterationSeconds = c->iterationSeconds;
  solution.cellVisits = c->cellVisits;
  solution.shadowRays = c->shadowRays;
  solution.directSeconds = c->directSeconds;
  return c;
}

// Writes the state after `done` iterations (0: the first shot alone) to the solve's file; true
// when it is there to go on from.
bool keepCheckpoint(const std::filesystem::path& file, int done, SideLight& light,
                    VoxelCheckpoint& kept, VoxelSolution& solution) {
  if (file.empty()) return false;
  kept.iterationsDone = done;
  kept.irradiance = light.irradiances();
  kept.bounce = light.gathered();
  kept.direct = solution.direct;
  kept.residuals = solution.residuals;
  kept.iterationSeconds = solution.iterationSeconds;
  kept.cellVisits = solution.cellVisits;
  kept.shadowRays = solution.shadowRays;
  kept.directSeconds = solution.directSeconds;
  const std::string warning = saveVoxelCheckpoint(file, kept);
  if (!warning.empty()) solution.warnings.push_back(warning);
  return warning.empty();
}

}  // namespace

VoxelSolution solveVoxelRadiosity(const Scene& scene, const VoxelGrid& grid,
                                  const RayCaster& caster, std::span<const Light> lights,
                                  const VoxelSolverSettings& settings,
                                  const ProgressCallback& progress) {
  VoxelSolution solution;
  const SweepDirections sweepDirections(settings);
  const DirectionSet& directions = sweepDirections.first;
  const DirectionSet& laterDirections = sweepDirections.later();
  solution.directions = directions.size();
  solution.laterDirections = laterDirections.size();
  // Checked first: a solve that cannot fit fails before its first shot, not an hour later.
  const size_t lines = widestLineTable(grid, sweepDirections);
  checkLineCount(grid, lines);
  checkMemory(grid, lines, settings);
  solution.sweepThreads = DiscreteLineSweep::threadCount();
  const std::filesystem::path checkpoint = voxelCheckpointFile(scene, grid, lights, settings);
  std::optional<VoxelCheckpoint> resumed = resumeFrom(checkpoint, grid.entryCount(), solution);
  const int firstIteration = resumed ? resumed->iterationsDone : 0;
  VoxelCheckpoint kept;  // the iterations' powers, for the tail and the next checkpoint
  std::vector<Color> h(grid.entryCount(), Color(0.0f));
  if (resumed) {
    h = std::move(resumed->irradiance);  // exact: H's 24-bit floats round-trip through floats
    solution.direct = std::move(resumed->direct);
    kept.bouncePower = std::move(resumed->bouncePower);
    kept.totalPower = resumed->totalPower;
  } else if (settings.directFirstShot) {
    const auto start = std::chrono::steady_clock::now();
    h = directIrradiance(scene, grid, caster, lights, settings, solution.shadowRays, progress);
    solution.directSeconds = secondsSince(start);
    if (settings.keepsDirect()) solution.direct = h;
  }
  SideLight light(grid, settings, directions, std::move(h));
  kept.sourcePower = resumed ? resumed->sourcePower : light.totalPower();
  const double putIn = luminance(kept.sourcePower);
  if (resumed) light.gathered() = std::move(resumed->bounce);
  if (firstIteration >= 2 && sweepDirections.coarser) light.normalizeFor(laterDirections);
  bool canResume = resumed.has_value();
  if (!resumed && settings.directFirstShot)
    canResume = keepCheckpoint(checkpoint, 0, light, kept, solution);
  auto sweep = std::make_unique<DiscreteLineSweep>(grid, SweepSettings{settings.tangentCorrection});
  sweep->reserveLines(lines);
  std::vector<DiscreteLineSweep::SentLight> packed(grid.entryCount());
  const auto pairsOf = [&](const DirectionSet& d) {
    const size_t pairs = d.pairCount(), blocks = pairBlocks(pairs);
    const auto [first, last] = settings.processes.block(blocks);
    return blockPairs(pairs, blocks, last).first - blockPairs(pairs, blocks, first).first;
  };
  // The sweeps this run expects, re-estimated after every iteration as the residuals fall.
  const double meanRho = meanReflectance(grid);
  const auto expectedPairs = [&] {
    const int iterations = expectedIterations(settings, solution.residuals, meanRho);
    const size_t later = size_t(std::max(iterations - std::max(firstIteration, 1), 0));
    return (firstIteration == 0 ? pairsOf(directions) : 0) + pairsOf(laterDirections) * later;
  };
  ProgressTicker ticker(progress, expectedPairs());
  bool converged = !solution.residuals.empty() && settings.tolerance > 0.0 &&
                   solution.residuals.back() < settings.tolerance;
  const auto start = std::chrono::steady_clock::now();
  for (int iteration = firstIteration; iteration < settings.iterations && !converged; ++iteration) {
    const auto iterationStart = std::chrono::steady_clock::now();
    const bool first = iteration == 0;
    const DirectionSet& swept = first ? directions : laterDirections;
    const DiscreteLineSweep::Source source = DiscreteLineSweep::packSides(
        grid, [&](size_t e) { return light.sends(e, first); }, packed);
    // Packed with the weights of the sweep that gathered it, the last bounce is spent: the
    // next one is normalized for the sphere it is swept on.
    if (iteration == 1 && sweepDirections.coarser) light.normalizeFor(laterDirections);
    try {
      gatherAllDirections(swept, *sweep, light.gathered(), source, settings, iteration, ticker);
    } catch (const Cancelled&) {
      if (!canResume) throw;
      throw Cancelled(
          fmt::format("the solve goes on from iteration {} of {} when run again "
                      "(checkpoint {})",
                      iteration + 1, settings.iterations, checkpoint.string()));
    }
    const auto [added, total] = light.addBounce();
    kept.bouncePower.push_back(added);
    kept.totalPower = total;
    solution.residuals.push_back(putIn > 0.0 ? luminance(added) / putIn : 0.0);
    solution.iterationSeconds.push_back(secondsSince(iterationStart));
    solution.cellVisits += uint64_t(grid.cellCount()) * swept.size();
    converged = settings.tolerance > 0.0 && solution.residuals.back() < settings.tolerance;
    if (iteration + 1 < settings.iterations && !converged) {
      canResume = keepCheckpoint(checkpoint, iteration + 1, light, kept, solution) || canResume;
      ticker.setTotal(expectedPairs());
    }
  }
  solution.converged = converged || !(putIn > 0.0);
  solution.sweepSeconds = secondsSince(start);
  const std::vector<Vec3d>& bouncePower = kept.bouncePower;
  const Color tail = settings.estimateTail ? tailFactor(bouncePower) : Color(0.0f);
  if (tail != Color(0.0f)) {
    light.addLastBounceTimes(tail);
    const double added = luminance(Vec3d(tail) * bouncePower.back());
    solution.tailShare = added / (luminance(kept.totalPower) + added);
  }
  solution.workingBytes =
      grid.entryCount() * voxelSolverBytesPerSide(settings) + sweep->workingBytes();
  // The sweep's arrays go before the results are made, so they never coexist.
  sweep.reset();
  releaseMemory(packed);
  light.releaseBounce();
  solution.radiosity = light.radiosities();
  solution.irradiance = light.irradiances();
  if (!checkpoint.empty()) {
    std::error_code ignored;
    std::filesystem::remove(checkpoint, ignored);  // done: nothing to go on from
  }
  return solution;
}

VoxelSolution solveVoxelRadiosity(const Scene& scene, const VoxelGrid& grid,
                                  const VoxelSolverSettings& settings,
                                  const ProgressCallback& progress) {
  const RayCaster caster(scene);
  return solveVoxelRadiosity(scene, grid, caster, scene.lights, settings, progress);
}

}  // namespace rad
