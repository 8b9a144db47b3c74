#pragma once
// Patch radiosity: the classical finite-element method. Every planar face is subdivided into
// patches (a quadtree per face), the form factors between patches are estimated (by ray casting
// by default) into a sparse table that is cached on disk, and the linear system
// B = E + rho F B is solved by Jacobi, Gauss-Seidel or progressive refinement.
// Based on: C. Goral, K. Torrance, D. Greenberg and B. Battaile, "Modeling the interaction of
// light between diffuse surfaces", SIGGRAPH 1984; M. Cohen and J. Wallace, "Radiosity and
// Realistic Image Synthesis", Academic Press 1993.

#include <radiosity/object_radiometry.h>
#include <radiosity/process_share.h>
#include <radiosity/progress.h>
#include <radiosity/ray_caster.h>
#include <radiosity/scene.h>
#include <radiosity/solver_settings.h>
#include <radiosity/surface_radiance.h>
#include <radiosity/surface_solution.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rad {

enum class PatchFormFactorEstimator { Hemisphere, Pairwise, Exact };
enum class PatchSolverKind { Jacobi, GaussSeidel, Progressive };
enum class PatchShading { Smooth, Flat };

inline constexpr NamedChoice<PatchFormFactorEstimator> kFormFactorEstimatorNames[] = {
    {"hemisphere", PatchFormFactorEstimator::Hemisphere},
    {"pairwise", PatchFormFactorEstimator::Pairwise},
    {"exact", PatchFormFactorEstimator::Exact}};
inline constexpr NamedChoice<PatchSolverKind> kPatchSolverNames[] = {
    {"gauss-seidel", PatchSolverKind::GaussSeidel},
    {"jacobi", PatchSolverKind::Jacobi},
    {"progressive", PatchSolverKind::Progressive}};
inline constexpr NamedChoice<PatchShading> kPatchShadingNames[] = {{"smooth", PatchShading::Smooth},
                                                                   {"flat", PatchShading::Flat}};

struct PatchRadiositySettings {
  float patchSize = 0.0f;  ///< longest patch edge in scene units; 0: from targetPatches
  /// When patchSize is 0: about this many patches beyond the one each face root is at least.
  size_t targetPatches = 4000;
  PatchFormFactorEstimator estimator = PatchFormFactorEstimator::Hemisphere;
  /// hemisphere: rays per patch; pairwise: point pairs per patch pair; exact: points per patch.
  int formFactorRays = 256;
  float formFactorThreshold = 0.0f;  ///< form factors below it are dropped from the table
  std::string cacheDir;              ///< directory of the form-factor cache; empty: no cache
  PatchSolverKind solver = PatchSolverKind::GaussSeidel;
  int maxIterations = 1000;  ///< sweeps (progressive: shots / patches)
  double tolerance = 1e-3;   ///< relative residual at which the solver stops
  PatchShading shading = PatchShading::Smooth;
  /// Points per patch (rounded up to a square) at which the direct light of point, spot and IES
  /// lights is averaged, one shadow ray per light each.
  int lightSamples = 16;
  /// Adaptive subdivision for point, spot and IES lights: patches crossed by a beam or shadow
  /// edge, or whose direct light differs from a neighbour's by more than refineThreshold
  /// (relative), are split, down to refineLevels levels below the base patch size (0: none).
  int refineLevels = 2;
  float refineThreshold = 0.5f;
  /// Solve each light group apart (light_groups.h; one solve of the system per group, on one
  /// mesh refined for all the lights), so that setGroupScales() rescales them without a solve.
  bool lightGroups = false;
  uint64_t seed = 1;
  /// The processes the form factors are split among (the hemisphere estimator's rows: each
  /// process casts a block, and all get every row; process_share.h); one by default.
  ProcessShare processes;
};

struct PatchRadiosityStats {
  size_t patches = 0, nodes = 0, vertices = 0;
  size_t basePatches = 0;    ///< patches before adaptive subdivision
  size_t refinedSplits = 0;  ///< patches split by adaptive subdivision
  int refineRounds = 0;
  float patchSize = 0.0f;
  uint64_t rays = 0;  ///< rays cast (form factors and lights)
  /// Emitter patches whose form-factor columns were computed exactly (hemisphere estimator; 0:
  /// none, the emitters were too many or the estimator is another).
  size_t exactColumns = 0;
  size_t nonZeros = 0;  ///< entries of the form-factor table (or of the rows computed)
  size_t tableBytes = 0;
  /// What the threshold dropped: of the entries, of the table's sum, of one row's sum at most,
  /// and the rows that lost more than 1% of their sum (the kept entries of a row are scaled
  /// back to its sum, so no light is lost, but it is moved).
  double droppedEntryFraction = 0.0, droppedSumFraction = 0.0, droppedWorstRowFraction = 0.0;
  uint64_t rowsDroppingOverOnePercent = 0;
  double rowSumMin = 0.0, rowSumMean = 0.0, rowSumMax = 0.0;  ///< closure of the rows computed
  /// Rows whose estimated sum exceeded 1 by more than the rays' noise (4 / sqrt(rays)), scaled
  /// back to 1 (no patch sends on more light than reaches it), and the largest estimated sum.
  uint64_t rowsScaledToClosure = 0;
  double rowSumEstimatedMax = 0.0;
  /// Patches whose reflected share (of the light they send, what comes back reflected; for a
  /// reciprocal row, its sum weighted by the reflectances) exceeded kMaxReflectance, scaled
  /// back to it so that no sweep can make the light grow (FormFactorTable::boundReflection),
  /// and the largest share before.
  uint64_t scaledForReflection = 0;
  double reflectedShareMax = 0.0;
  bool cacheLoaded = false;
  std::string cacheFile;   ///< empty without a cache
  uint64_t lightRays = 0;  ///< shadow rays toward point, spot and IES lights
  double meshSeconds = 0.0, formFactorSeconds = 0.0, cacheLoadSeconds = 0.0, solveSeconds = 0.0;
  double lightSeconds = 0.0;  ///< direct light of the analytic lights
  /// Form-factor rows cast for this solve, and kept from the model's earlier solves or the disk
  /// cache (the hemisphere estimator's master table by node; the others compute all or none).
  size_t rowsComputed = 0, rowsReused = 0;
  size_t masterRows = 0;  ///< node rows the model's master table holds
  std::string solver;
  int iterations = 0;
  uint64_t shots = 0;
  std::vector<double> residuals;  ///< relative residual per sweep
  /// The residual fell below the tolerance (with light groups: in every group's solve); when
  /// not, a warning says by how much and what to change.
  bool converged = false;
  /// Stopped early: the residual rose sweep after sweep (patch_solvers.h).
  bool diverging = false;
  size_t memoryBytes = 0;             ///< mesh, table and solution arrays
  std::vector<std::string> warnings;  ///< e.g. a cache file that could not be used
};

class PatchRadiosity;

/// The half of the patch method done once per geometry: the base mesh, and the master
/// form-factor table: the rows of every quadtree node solved so far (adaptive subdivision makes
/// the patches depend on the lights; a solve casts only the rows of nodes never solved before),
/// read from and saved to the disk cache, keyed by the geometry and the base meshing.
/// solve() is the half done per light state.
class PatchModel {
 public:
  /// Meshes `scene` at the base level. `caster` is built over the same scene and shared with
  /// every stage of a run; scene and caster must outlive the model and its solutions. Throws
  /// InputError for bad settings.
  PatchModel(const Scene& scene, const RayCaster& caster, const PatchRadiositySettings& settings);
  /// The same with a ray caster of its own.
  PatchModel(const Scene& scene, const PatchRadiositySettings& settings);
  ~PatchModel();
  PatchModel(PatchModel&&) noexcept;
  PatchModel& operator=(PatchModel&&) noexcept;

  /// The solution with `lights` in place of the scene's own (emitting surfaces as the scene
  /// has them): their direct light on the patches and the subdivision it asks for, the form
  /// factors of the resulting patches (kept from an earlier solve, read from the disk cache or
  /// computed), and the bounces. Thread-safe. Throws rad::Cancelled if `progress` returns false;
  /// a bad cache file is a warning.
  PatchRadiosity solve(std::span<const Light> lights, const ProgressCallback& progress = {}) const;
  /// The same with the lights' direct light shadowed by what `shadowCaster` holds (the scene
  /// with its dynamic objects placed: Scene::withDynamicObjectsAt), which must outlive the call.
  PatchRadiosity solve(std::span<const Light> lights, const RayCaster& shadowCaster,
                       const ProgressCallback& progress = {}) const;
  /// The solution a solution file (solution_file.h) keeps, saved from a model of this scene and
  /// settings solved for `lights`, without solving: its patches, and its light per group when
  /// they were solved apart (at the scales it was saved with). Throws InputError naming the file
  /// for one that is truncated, corrupt, of another version, of another method, scene, lights
  /// or patch settings.
  PatchRadiosity load(const std::string& path, std::span<const Light> lights) const;

  struct State;

 private:
  friend class Relighter;
  std::shared_ptr<State> state_;
};

/// The solved scene; a SurfaceSolution that interpolates irradiance smoothly across patches.
class PatchRadiosity : public SurfaceSolution {
 public:
  /// Meshes and solves `scene` under its own lights (PatchModel and solve in one); the scene
  /// must outlive the result. Throws InputError for bad settings and rad::Cancelled if
  /// `progress` returns false. A bad cache file is a warning.
  PatchRadiosity(const Scene& scene, const PatchRadiositySettings& settings,
                 const ProgressCallback& progress = {});
  ~PatchRadiosity() override;
  PatchRadiosity(PatchRadiosity&&) noexcept;
  PatchRadiosity& operator=(PatchRadiosity&&) noexcept;

  /// Ke + rho H / pi at the hit: H interpolated from the vertex averages (smooth) or the
  /// patch's own (flat); 0 from the back of a one-sided face.
  Color radiance(const SurfaceHit& hit) const override;
  bool hasIndirectIrradiance() const override { return true; }
  /// The lights it was solved with.
  /// The lights it was solved with (with light groups, each times its group's scale).
  std::span<const Light> directLights() const override;
  std::span<const Color> emissionScales() const override;
  Color irradiance(const SurfaceHit& hit) const override;
  /// H less the lights' D and what the emitting patches send directly, interpolated as
  /// radiance() interpolates H.
  Color indirectIrradiance(const SurfaceHit& hit) const override;
  const Scene& scene() const override;
  /// Its patches (a two-sided face's back as its mirrored patches).
  size_t elementCount() const override;
  SurfaceElement element(size_t patch) const override;
  /// The patch mesh: one node per scene object, its patches (a two-sided face's back as its
  /// mirrored patches, with the back's own light; every triangle one-sided), vertex colours
  /// Ke + rho H / pi (H as radiance() interpolates it).
  LitMesh litMesh() const override;
  /// With settings.lightGroups: the groups, each solved on the same patches.
  std::span<const LightGroup> lightGroups() const override;
  std::span<const Color> groupScales() const override;
  void setGroupScales(std::span<const Color> scales) override;
  Color groupRadiosity(size_t group, size_t patch) const override;
  const PatchRadiosityStats& stats() const;
  /// The stats as every method reports them (SolveReport), for the commands and the stats file.
  SolveReport report() const override;
  /// Writes the solution file `path` (solution_file.h), atomically; `settings`: those it was
  /// solved with, which the file records (resolveMethodSettings makes the model that loads it).
  /// Throws std::runtime_error if it cannot be written.
  void save(const std::string& path, const SolverSettings& settings) const override;

 private:
  friend class PatchModel;
  friend class Relighter;
  PatchRadiosity(std::shared_ptr<const PatchModel::State> model, std::span<const Light> lights,
                 const RayCaster* shadowCaster, const ProgressCallback& progress);
  struct Impl;
  explicit PatchRadiosity(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// The cache directory the CLI uses by default: $XDG_CACHE_HOME/radiosity, else
/// $HOME/.cache/radiosity, else empty.
std::string defaultPatchCacheDir();

}  // namespace rad
