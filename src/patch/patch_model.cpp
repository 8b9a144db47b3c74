// PatchModel: the patch method's half done once per geometry: the base mesh and the master
// form-factor table (read from the disk cache when there is one).
#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/process_memory.h>

#include <chrono>
#include <cmath>

#include "patch/patch_model_state.h"

namespace rad {

namespace {

void validatePatchSettings(const PatchRadiositySettings& s) {
  auto fail = [](const std::string& what) { throw InputError("patch settings", what); };
  // The patch size and count are checked where the mesh is built (PatchMesh).
  if (s.formFactorRays < 1)
    fail(fmt::format("form-factor rays {} must be at least 1", s.formFactorRays));
  if (!(s.formFactorThreshold >= 0.0f && s.formFactorThreshold < 1.0f))
    fail(fmt::format("form-factor threshold {} out of range [0, 1)", s.formFactorThreshold));
  if (s.lightSamples < 1) fail(fmt::format("light samples {} must be at least 1", s.lightSamples));
  if (s.refineLevels < 0 || s.refineLevels > 8)
    fail(fmt::format("refine levels {} out of range [0, 8]", s.refineLevels));
  if (!(s.refineThreshold > 0.0f) || !std::isfinite(s.refineThreshold))
    fail(fmt::format("refine threshold {} must be positive", s.refineThreshold));
  if (s.maxIterations < 1)
    fail(fmt::format("max iterations {} must be at least 1", s.maxIterations));
  if (!(s.tolerance >= 0.0)) fail(fmt::format("tolerance {} must not be negative", s.tolerance));
}

// Bytes per base patch at a solve's peak (mesh, hemisphere hits, master rows, table, solver
// arrays): 15 KB at 256 rays, measured on room:2 between 5,232 and 20,916 patches (106 and 341
// MB). The pairwise and exact estimators' rows hold an entry for every patch seen: up to n.
double patchSolveBytes(double patches, const PatchRadiositySettings& s) {
  const double perRow =
      s.estimator == PatchFormFactorEstimator::Hemisphere ? 56.0 * s.formFactorRays : 8.0 * patches;
  return patches * (1024.0 + perRow);
}

// The patch size to mesh with, after refusing one whose solve would not fit in memory (a size
// far below the scene's scale asks for billions of patches). A bad size or count is left for
// PatchMesh to refuse.
float checkedPatchSize(const Scene& scene, const PatchRadiositySettings& s) {
  const bool sized = s.patchSize > 0.0f && std::isfinite(s.patchSize);
  if (!sized && !(s.patchSize == 0.0f && s.targetPatches >= 1)) return s.patchSize;
  const float size = sized ? s.patchSize : PatchMesh::patchSizeFor(scene, s.targetPatches);
  const double patches = PatchMesh::patchCountFor(scene, size);
  requireMemory(patchSolveBytes(patches, s), "patch settings",
                fmt::format("patch size {:g} gives about {:.0f} patches, which", size, patches),
                "use fewer patches or a larger patch size");
  return size;
}

// The base mesh before any ray caster: a mesh too large to hold fails first, as "out of memory".
std::shared_ptr<PatchModel::State> meshedState(const Scene& scene,
                                               const PatchRadiositySettings& settings) {
  validatePatchSettings(settings);
  auto state = std::make_shared<PatchModel::State>();
  state->scene = &scene;
  state->settings = settings;
  const auto start = std::chrono::steady_clock::now();
  state->baseMesh = std::make_unique<PatchMesh>(
      scene, PatchMeshSettings{checkedPatchSize(scene, settings), settings.targetPatches});
  state->meshSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const PatchMesh& mesh = *state->baseMesh;
  state->basePatchOf.assign(mesh.nodes().size(), kNoPatch);
  for (uint32_t p = 0; p < mesh.size(); ++p) state->basePatchOf[mesh.patches()[p].node] = p;
  if (settings.estimator == PatchFormFactorEstimator::Hemisphere) {
    state->master = std::make_unique<MasterFormFactorTable>(settings.refineLevels,
                                                            settings.formFactorRays, settings.seed);
    if (!settings.cacheDir.empty()) {
      state->masterKey = masterTableCacheKey(scene, mesh, settings.refineLevels,
                                             settings.formFactorRays, settings.seed);
      state->masterFile = masterTableCacheFile(settings.cacheDir, state->masterKey);
      state->masterWarning = state->master->load(state->masterFile, state->masterKey);
      state->master->keepOnDisk(state->masterFile, state->masterKey);
      state->masterLoaded = state->master->rows() > 0;
    }
  }
  return state;
}

}  // namespace

PatchModel::PatchModel(const Scene& scene, const RayCaster& caster,
                       const PatchRadiositySettings& settings)
    : state_(meshedState(scene, settings)) {
  state_->caster = &caster;
}

PatchModel::PatchModel(const Scene& scene, const PatchRadiositySettings& settings)
    : state_(meshedState(scene, settings)) {
  state_->ownCaster = std::make_unique<RayCaster>(scene);
  state_->caster = state_->ownCaster.get();
}

PatchModel::~PatchModel() = default;
PatchModel::PatchModel(PatchModel&&) noexcept = default;
PatchModel& PatchModel::operator=(PatchModel&&) noexcept = default;

PatchRadiosity PatchModel::solve(std::span<const Light> lights,
                                 const ProgressCallback& progress) const {
  return PatchRadiosity(state_, lights, nullptr, progress);
}

PatchRadiosity PatchModel::solve(std::span<const Light> lights, const RayCaster& shadowCaster,
                                 const ProgressCallback& progress) const {
  return PatchRadiosity(state_, lights, &shadowCaster, progress);
}

}  // namespace rad
