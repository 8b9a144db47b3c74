#pragma once
// What a PatchRadiosity holds, for the code that makes one: its constructor and the Relighter,
// which keeps one up to date as the lights move.

#include <radiosity/patch_radiosity.h>

#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "lighting/light_group_mix.h"
#include "patch/form_factor_table.h"
#include "patch/light_refinement.h"
#include "patch/patch_mesh.h"
#include "patch/patch_model_state.h"
#include "patch/patch_solvers.h"

namespace rad {

class ByteReader;
struct SolutionFile;

struct PatchRadiosity::Impl {
  std::shared_ptr<const PatchModel::State> model;
  const Scene* scene = nullptr;
  PatchRadiositySettings settings;
  std::vector<Light> lights;        ///< those it is solved with
  std::unique_ptr<PatchMesh> mesh;  ///< the model's base mesh, refined for the lights
  PatchSolution solution;
  std::vector<Color> vertexIrradiance;
  std::vector<Color> indirect, vertexIndirect;  ///< H less the direct light (patch, vertex)
  std::vector<HangingVertex> hanging;           ///< of the refined mesh
  PatchRadiosityStats stats;
  std::vector<Color> lightDirect;  ///< D per patch (empty: no lights)

  /// The light groups, when solved apart: per group, its D, H and indirect H per patch, which
  /// `solution` and `indirect` combine at the mix's scales.
  LightGroupMix mix;
  std::vector<std::vector<Color>> groupDirect, groupIrradiance, groupIndirect;

  /// What shadows the lights' direct light in build() (the scene with its dynamic objects
  /// placed); null: the model's caster.
  const RayCaster* shadowCaster = nullptr;
  bool keepTable = false;                ///< keep the form factors (for relighting)
  bool saveMaster = true;                ///< save the master table when rows were cast
  std::optional<FormFactorTable> table;  ///< the form factors of the patches, when kept
  /// The last table assembled is the symmetrized one: its closure scaled no row and no
  /// threshold applied (so a relighter can update it for a changed quadtree).
  bool tableSymmetrizedOnly = false;
  /// The table before the kept one, when formFactorsAfter() replaced it and it is small enough
  /// to keep: the next table made so takes its arrays.
  std::optional<FormFactorTable> spareTable;

  /// Takes the model's base mesh, to be lit and solved for `lights` by build().
  Impl(std::shared_ptr<const PatchModel::State> model, std::span<const Light> lights);
  /// Lights the patches (refining the mesh, with the lights' values on nodes from and into
  /// `cache`), gets the form factors, solves and shades.
  void build(PatchLightCache& cache, const ProgressCallback& progress);
  /// The equation's terms on the mesh: E, rho, area, and D (zeros without lights).
  PatchSystem system() const;
  /// The vertex values radiance() interpolates, from the solution and the indirect light.
  void shadeVertices();
  void recordMesh();

  FormFactorSettings ff;             ///< the estimator's settings, fixed once per solve
  std::vector<uint8_t> emitterRows;  ///< per patch: it emits (the threshold keeps its row whole)
  void chooseFormFactorSettings();
  void warnOfCutOutTargets();
  /// The form factors of the patches, with their numbers (entries, bytes, threshold loss, row
  /// sums) put in the stats.
  FormFactorTable formFactors(const RayCaster& caster, const ProgressCallback& progress);
  FormFactorTable loadOrComputeFormFactors(const RayCaster& caster,
                                           const ProgressCallback& progress);
  /// formFactors() for `mesh`, refined anew from the base mesh after `before` (whose exact
  /// columns were `beforeExact`): the kept table of `before` updated for the patches that split
  /// or merged (patch/table_update.h) where it is the symmetrized one, else assembled anew.
  FormFactorTable formFactorsAfter(const PatchMesh& before, std::span<const uint32_t> beforeExact,
                                   const RayCaster& caster);
  /// Scales back the rows past closure (FormFactorTable::closeRows), with its numbers in the
  /// stats and tableSymmetrizedOnly.
  void closeTable(FormFactorTable& table);
  /// Scales back the rows whose reflected share passes kMaxReflectance
  /// (FormFactorTable::boundReflection: every sweep then contracts), with its numbers in the
  /// stats and tableSymmetrizedOnly. The materials' part of the closure: done on every table
  /// the solvers get, after the disk cache, which is keyed without the materials.
  void boundReflection(FormFactorTable& table);
  /// Puts a table's numbers (entries, bytes, threshold loss, row sums) in the stats.
  void recordTable(const FormFactorTable& table);
  /// The table of rows as the estimators give them: made reciprocal, closed (closeRows), then
  /// thresholded; the closure's numbers go into the stats.
  FormFactorTable assembleTable(FormFactorRows rows);
  void solve(const RayCaster& caster, const ProgressCallback& progress);
  PatchSolution solveSystem(const FormFactorTable& table, const PatchSystem& system,
                            const ProgressCallback& progress) const;
  /// A solve per light group (its emitters alone), then their combination.
  void solveGroups(const FormFactorTable& table, const ProgressCallback& progress);
  /// solution and indirect from the groups' arrays at the mix's scales.
  void combineGroups();
  void solveLazily(const RayCaster& caster, const PatchSystem& system,
                   const ProgressCallback& progress);
  void closeRow(std::vector<FormFactorEntry>& row);
  void lightPatches(const RayCaster& caster, PatchLightCache& cache,
                    const ProgressCallback& progress);
  void recordThresholdLoss(const ThresholdLoss& loss);
  void warnOfThresholdLoss();
  /// Warns that boundReflection scaled patches back (light lost where rho is near 1).
  void warnOfReflectionBound();
  /// Records whether the solve converged and, when not, warns with its residual, the
  /// tolerance and what to change.
  void reportConvergence();
  /// What bounced at least once: H less D and less what the emitters send directly.
  std::vector<Color> indirectOf(const PatchSolution& solved, const FormFactorRowSource& rows,
                                const PatchSystem& system) const;
  std::vector<Color> averageAtVertices(const std::vector<Color>& perPatch) const;
  /// A per-patch quantity at a hit: interpolated from the vertex averages (smooth) or the
  /// patch's own (flat); nullopt on the back of a one-sided face.
  std::optional<Color> interpolate(const SurfaceHit& hit, const std::vector<Color>& perPatch,
                                   const std::vector<Color>& perVertex) const;
  LitMesh litMesh() const;
  /// A solution file's payload (patch_solution_file.cpp), into a solution of the base mesh.
  void readSolution(const SolutionFile& file, ByteReader in);
};

}  // namespace rad
