#pragma once
// Voxel (discrete) radiosity: the quasi-linear method that sweeps the directions of a digital
// sphere, splits the voxels into parallel 3D discrete lines and exchanges light between
// consecutive voxels of each line. O(N) memory, no ray traversal in the sweeps.
// Based on: P. Chatelier and R. Malgouyres, "A low-complexity discrete radiosity method",
// Computers & Graphics 30(1), 2006.

#include <radiosity/object_radiometry.h>
#include <radiosity/process_share.h>
#include <radiosity/progress.h>
#include <radiosity/ray_caster.h>
#include <radiosity/scene.h>
#include <radiosity/surface_radiance.h>
#include <radiosity/surface_solution.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace rad {

struct VoxelRadiositySettings {
  float voxelSize = 0.0f;        ///< voxel edge in scene units; 0: from targetVoxels
  size_t targetVoxels = 200000;  ///< approximate number of surface voxels when voxelSize is 0
  int sphereRadius = 38;         ///< radius R of the digital sphere (R = 38: 14,790 directions)
  /// R for the sweeps after the first, whose light (the second bounce on) is smoother: a coarser
  /// sphere costs less, as R^2. 0: sphereRadius, as in the paper.
  int laterSphereRadius = 0;
  /// Sweeps over all directions at most: the cap of a solve to the tolerance, or with
  /// tolerance 0 the count (the paper's six).
  int iterations = 100;
  /// Stop once the light still bouncing (the power the last iteration added to B) is below
  /// this share of the light put in, as the patch method's residual; 0: every iteration.
  double tolerance = 1e-3;
  /// Add the light of the bounces after the last iteration, extrapolated from the last two
  /// (their power falls geometrically).
  bool estimateTail = true;
  bool tangentCorrection = true;  ///< look through voxels a line only grazes
  bool directFirstShot = true;    ///< direct light by shadow rays; the sweeps carry the rest
  int directSamples = 64;         ///< shadow-ray samples per voxel side for the first shot
  bool normalize = true;          ///< per-voxel normalization of the direction factors
  bool jitterLines = true;        ///< shift each direction's lines anew every iteration
  /// Keep the first shot's direct light apart from the bounces (12 more bytes a side through
  /// the solve), so that pictures can take the direct light per pixel (indirectIrradiance).
  bool keepDirectLight = false;
  /// Solve each light group apart (light_groups.h; a first shot and sweeps per group), so that
  /// setGroupScales() rescales them without a solve.
  bool lightGroups = false;
  uint64_t seed = 1;
  /// Where the solve keeps a checkpoint after every iteration (written atomically, removed when
  /// it is done) and goes on from one when solved again after a kill or Ctrl-C, to the same
  /// answer (bit for bit with the same threads); empty: none. Not with processes split.
  std::string checkpointDir;
  /// The processes the solve is split among (each sweeps a block of every iteration's
  /// direction pairs and shoots a block of the sides' direct light); one by default.
  ProcessShare processes;
};

struct VoxelRadiosityStats {
  size_t voxels = 0;  ///< occupied voxels (cells)
  size_t sides = 0;   ///< voxel sides (entries): one per surface orientation in a cell
  size_t directions = 0;
  size_t laterDirections = 0;  ///< directions of the sweeps after the first
  float voxelSize = 0.0f;
  uint64_t visits = 0;  ///< voxel-direction visits of all sweeps
  uint64_t shadowRays = 0;
  /// Each iteration's relative residual: the power (area-weighted luminance) of the light it
  /// added, still bouncing, over that of the light put in (B's before the sweeps).
  std::vector<double> residuals;
  /// The residual fell below the tolerance (with light groups: in every group's solve); not
  /// with tolerance 0 (a count of iterations). When not, with a tolerance, a warning says by
  /// how much and what to change.
  bool converged = false;
  double tailShare = 0.0;  ///< share of B's power the tail estimate added
  double voxelizeSeconds = 0.0, directSeconds = 0.0, sweepSeconds = 0.0;
  /// The sweeps' time in each iteration: their spread shows how steady the machine was.
  std::vector<double> iterationSeconds;
  size_t memoryBytes = 0;  ///< grid and solver arrays
  /// Threads that shared each direction's sweep (results are the same for any number).
  size_t sweepThreads = 0;
  std::vector<std::string> warnings;  ///< settings that lose light or speed, and why
  int resumedIterations = 0;  ///< iterations a checkpoint brought (0: solved from the start)
};

class VoxelRadiosity;

/// The half of the voxel method done once per geometry: the voxel grid. solve() is the half done
/// per light state (the first shot of the lights, the sweeps).
class VoxelModel {
 public:
  /// Voxelizes `scene`. `caster` is built over the same scene and shared with every stage of a
  /// run; scene and caster must outlive the model and its solutions. Throws InputError for bad
  /// settings.
  VoxelModel(const Scene& scene, const RayCaster& caster, const VoxelRadiositySettings& settings);
  /// The same with a ray caster of its own.
  VoxelModel(const Scene& scene, const VoxelRadiositySettings& settings);
  ~VoxelModel();
  VoxelModel(VoxelModel&&) noexcept;
  VoxelModel& operator=(VoxelModel&&) noexcept;

  /// The solution with `lights` in place of the scene's own (emitting surfaces as the scene has
  /// them). Thread-safe. Throws InputError if memory would not hold the solve, rad::Cancelled if
  /// `progress` returns false.
  VoxelRadiosity solve(std::span<const Light> lights, const ProgressCallback& progress = {}) const;
  /// The same with the first shot shadowed by what `shadowCaster` holds (the scene with its
  /// dynamic objects placed: Scene::withDynamicObjectsAt), which must outlive the call.
  VoxelRadiosity solve(std::span<const Light> lights, const RayCaster& shadowCaster,
                       const ProgressCallback& progress = {}) const;
  /// The solution a solution file (solution_file.h) keeps, saved from a model of this scene and
  /// settings solved for `lights`, without solving (its light per group when they were solved
  /// apart, at the scales it was saved with). Throws InputError naming the file for one that is
  /// truncated, corrupt, of another version, of another method, scene, lights or voxel grid.
  VoxelRadiosity load(const std::string& path, std::span<const Light> lights) const;

  struct State;

 private:
  std::shared_ptr<State> state_;
};

/// The solved scene; a SurfaceRadiance that interpolates the voxels' irradiance smoothly.
class VoxelRadiosity : public SurfaceSolution {
 public:
  /// Voxelizes and solves `scene` under its own lights (VoxelModel and solve in one); the scene
  /// must outlive the result. Throws InputError for bad settings and rad::Cancelled if
  /// `progress` returns false.
  VoxelRadiosity(const Scene& scene, const VoxelRadiositySettings& settings,
                 const ProgressCallback& progress = {});
  ~VoxelRadiosity() override;
  VoxelRadiosity(VoxelRadiosity&&) noexcept;
  VoxelRadiosity& operator=(VoxelRadiosity&&) noexcept;

  /// Ke + rho H / pi at the hit, with H interpolated from the voxel sides facing the hit's way.
  Color radiance(const SurfaceHit& hit) const override;
  Color irradiance(const SurfaceHit& hit) const override;
  /// With keepDirectLight and the first shot: the bounces' irradiance, interpolated as H is.
  bool hasIndirectIrradiance() const override;
  Color indirectIrradiance(const SurfaceHit& hit) const override;
  /// The lights it was solved with (with light groups, each times its group's scale).
  std::span<const Light> directLights() const override;
  std::span<const Color> emissionScales() const override;
  const Scene& scene() const override;
  /// Its voxel sides.
  size_t elementCount() const override;
  SurfaceElement element(size_t side) const override;
  /// The scene's triangles cut into triangles no longer than a voxel, vertex colours the
  /// radiance radiance() gives there, one node per object.
  LitMesh litMesh() const override;
  /// With settings.lightGroups: the groups, each solved on the same voxels.
  std::span<const LightGroup> lightGroups() const override;
  std::span<const Color> groupScales() const override;
  void setGroupScales(std::span<const Color> scales) override;
  Color groupRadiosity(size_t group, size_t side) const override;
  const VoxelRadiosityStats& stats() const;
  /// The stats as every method reports them (SolveReport), for the commands and the stats file.
  SolveReport report() const override;
  /// Writes the solution file `path` (solution_file.h), atomically; `settings`: those it was
  /// solved with, which the file records. Throws std::runtime_error if it cannot be written.
  void save(const std::string& path, const SolverSettings& settings) const override;

 private:
  friend class VoxelModel;
  VoxelRadiosity(std::shared_ptr<const VoxelModel::State> model, std::span<const Light> lights,
                 const RayCaster* shadowCaster, const ProgressCallback& progress);
  struct Impl;
  explicit VoxelRadiosity(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// The voxel size that gives about `targetVoxels` surface voxels for this scene (what
/// VoxelRadiositySettings::targetVoxels becomes).
float voxelSizeForCount(const Scene& scene, size_t targetVoxels);

}  // namespace rad
