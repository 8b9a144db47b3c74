// The public face of the voxel method: voxelize, solve, then answer radiance queries.
#include <fmt/format.h>
#include <radiosity/baked_mesh.h>
#include <radiosity/error.h>
#include <radiosity/voxel_radiosity.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <glm/gtc/constants.hpp>

#include "core/convergence_advice.h"
#include "core/vector_memory.h"
#include "voxel/voxel_radiosity_impl.h"
#include "voxel/voxelizer.h"

namespace rad {

namespace {

void validate(const VoxelRadiositySettings& s) {
  auto fail = [](const std::string& what) { throw InputError("voxel settings", what); };
  if (!(s.voxelSize >= 0.0f) || !std::isfinite(s.voxelSize))
    fail(fmt::format("voxel size {} must be positive", s.voxelSize));
  if (s.voxelSize == 0.0f && s.targetVoxels < 1) fail("voxel count must be at least 1");
  if (s.sphereRadius < 1 || s.sphereRadius > 200)
    fail(fmt::format("sphere radius {} out of range [1, 200]", s.sphereRadius));
  if (s.laterSphereRadius < 0 || s.laterSphereRadius > 200)
    fail(fmt::format("later sphere radius {} out of range [0, 200]", s.laterSphereRadius));
  if (s.iterations < 1) fail(fmt::format("iterations {} must be at least 1", s.iterations));
  if (s.tolerance < 0.0) fail(fmt::format("tolerance {} must not be negative", s.tolerance));
  if (s.directSamples < 1)
    fail(fmt::format("direct samples {} must be at least 1", s.directSamples));
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::shared_ptr<VoxelModel::State> voxelizedState(const Scene& scene,
                                                  const VoxelRadiositySettings& settings) {
  validate(settings);
  auto state = std::make_shared<VoxelModel::State>();
  state->scene = &scene;
  state->settings = settings;
  const auto start = std::chrono::steady_clock::now();
  state->grid = voxelizeScene(scene, {settings.voxelSize, settings.targetVoxels});
  state->voxelizeSeconds = secondsSince(start);
  return state;
}

VoxelSolverSettings solverSettings(const VoxelRadiositySettings& settings) {
  VoxelSolverSettings solver{settings, {}};
  // A split solve keeps no checkpoint: each process would keep its own part of one.
  if (settings.processes.split()) solver.checkpointDir.clear();
  return solver;
}

// At the cap above the tolerance: the light still bouncing is left to the tail estimate. The
// numbers, what to change, and, at the last iterations' rate of fall, how many more it wants.
std::string notConvergedWarning(const VoxelRadiosityStats& s,
                                const VoxelRadiositySettings& settings, const VoxelGrid& grid) {
  const std::vector<double>& r = s.residuals;
  const double last = r.empty() ? 0.0 : r.back();
  float rhoMax = 0.0f;
  for (const VoxelSurface& surface : grid.surfaces)
    rhoMax = std::max(rhoMax, maxComponent(surface.material.rho));
  return fmt::format(
      "voxel solve not converged: {:.3g} of the light put in still bouncing after {} iterations "
      "(--iterations {}), above --tolerance {:g}; the tail estimate added {:.1f}% of B for it; "
      "raise --iterations{} or --tolerance{}",
      last, r.size(), settings.iterations, settings.tolerance, 100.0 * s.tailShare,
      remainingStepsAdvice(r, settings.tolerance, "iteration"), nearWhiteAdvice(rhoMax));
}

}  // namespace

std::pair<VoxelSolution, std::vector<Color>> VoxelRadiosity::Impl::solve(
    std::span<const Light> lights, const VoxelSolverSettings& solver,
    const ProgressCallback& progress) const {
  // A checkpoint's key is the scene's: not for a first shot shadowed by placed dynamic objects.
  VoxelSolverSettings settings = solver;
  if (shadowCaster) settings.checkpointDir.clear();
  VoxelSolution solved = solveVoxelRadiosity(
      *scene, grid, shadowCaster ? *shadowCaster : *model->caster, lights, settings, progress);
  std::vector<Color> h;
  if (solver.keepsDirect()) {
    h = solved.irradiance;
    for (size_t e = 0; e < h.size(); ++e) h[e] = glm::max(h[e] - solved.direct[e], Color(0.0f));
    releaseMemory(solved.direct);
  }
  return {std::move(solved), std::move(h)};
}

// A solve per group (its lights and its materials' emission alone); the numbers of the solution
// are the groups' together (rays, visits, seconds summed; residuals in group order).
void VoxelRadiosity::Impl::solveGroups(VoxelSolverSettings solver,
                                       const ProgressCallback& progress) {
  const size_t groups = mix.groups().size();
  for (size_t g = 0; g < groups; ++g) {
    solver.emissionScales.assign(scene->materials.size(), Color(0.0f));
    for (uint32_t m : mix.groups()[g].materials) solver.emissionScales[m] = Color(1.0f);
    const std::vector<Light> own = mix.lightsOf(g);
    auto [solved, h] = solve(own, solver, progressPart(progress, g, groups));
    groupIrradiance.push_back(std::move(solved.irradiance));
    if (!h.empty()) groupIndirect.push_back(std::move(h));
    VoxelSolution& all = solution;
    if (g == 0)
      all = std::move(solved);
    else {
      all.converged = all.converged && solved.converged;
      all.cellVisits += solved.cellVisits;
      all.shadowRays += solved.shadowRays;
      all.directSeconds += solved.directSeconds;
      all.sweepSeconds += solved.sweepSeconds;
      all.residuals.insert(all.residuals.end(), solved.residuals.begin(), solved.residuals.end());
      all.iterationSeconds.insert(all.iterationSeconds.end(), solved.iterationSeconds.begin(),
                                  solved.iterationSeconds.end());
      all.resumedIterations += solved.resumedIterations;
      all.warnings.insert(all.warnings.end(), solved.warnings.begin(), solved.warnings.end());
    }
  }
  combineGroups();
}

Color VoxelRadiosity::Impl::emission(size_t side) const {
  const VoxelSurface& s = grid.surfaces[grid.surface[side]];
  if (s.emitter == VoxelSurface::kNoEmitter || mix.emissionScales().empty())
    return s.material.emission;
  return s.material.emission * mix.emissionScales()[s.emitter];
}

void VoxelRadiosity::Impl::combineGroups() {
  solution.irradiance = mix.combine(groupIrradiance);
  if (!groupIndirect.empty()) indirect = mix.combine(groupIndirect);
  solution.radiosity.resize(solution.irradiance.size());
  for (size_t e = 0; e < solution.radiosity.size(); ++e)
    solution.radiosity[e] =
        glm::pi<float>() * emission(e) + grid.materialOf(e).rho * solution.irradiance[e];
}

VoxelModel::VoxelModel(const Scene& scene, const RayCaster& caster,
                       const VoxelRadiositySettings& settings)
    : state_(voxelizedState(scene, settings)) {
  state_->caster = &caster;
}

VoxelModel::VoxelModel(const Scene& scene, const VoxelRadiositySettings& settings)
    : state_(voxelizedState(scene, settings)) {
  state_->ownCaster = std::make_unique<RayCaster>(scene);
  state_->caster = state_->ownCaster.get();
}

VoxelModel::~VoxelModel() = default;
VoxelModel::VoxelModel(VoxelModel&&) noexcept = default;
VoxelModel& VoxelModel::operator=(VoxelModel&&) noexcept = default;

VoxelRadiosity VoxelModel::solve(std::span<const Light> lights,
                                 const ProgressCallback& progress) const {
  return VoxelRadiosity(state_, lights, nullptr, progress);
}

VoxelRadiosity VoxelModel::solve(std::span<const Light> lights, const RayCaster& shadowCaster,
                                 const ProgressCallback& progress) const {
  return VoxelRadiosity(state_, lights, &shadowCaster, progress);
}

VoxelRadiosity::VoxelRadiosity(const Scene& scene, const VoxelRadiositySettings& settings,
                               const ProgressCallback& progress)
    : VoxelRadiosity(VoxelModel(scene, settings).solve(scene.lights, progress)) {}

VoxelRadiosity::VoxelRadiosity(std::shared_ptr<const VoxelModel::State> model,
                               std::span<const Light> lights, const RayCaster* shadowCaster,
                               const ProgressCallback& progress)
    : impl_(std::make_unique<Impl>(model, lights)) {
  impl_->shadowCaster = shadowCaster;
  const Scene& scene = *impl_->scene;
  const VoxelRadiositySettings& settings = model->settings;
  impl_->stats.voxelizeSeconds = model->voxelizeSeconds;

  const bool emittingSurfaces = std::any_of(scene.materials.begin(), scene.materials.end(),
                                            [](const Material& m) { return m.emits(); });
  if (!settings.directFirstShot && !impl_->lights.empty() && !emittingSurfaces)
    throw InputError(
        "voxel settings",
        fmt::format("without the first shot (--no-first-shot) the scene's {} "
                    "light(s) (point, spot, IES, sun, sky), all its light, reach no voxel: the "
                    "solution would be black",
                    impl_->lights.size()));
  const VoxelSolverSettings solver = solverSettings(settings);
  impl_->mix = LightGroupMix(scene, impl_->lights, settings.lightGroups);
  if (impl_->mix.apart())
    impl_->solveGroups(solver, progress);
  else
    std::tie(impl_->solution, impl_->indirect) = impl_->solve(impl_->lights, solver, progress);
  impl_->shadowCaster = nullptr;  // only for this solve

  VoxelRadiosityStats& s = impl_->stats;
  const VoxelSolution& solution = impl_->solution;
  if (!settings.directFirstShot && !impl_->lights.empty())
    s.warnings.push_back(
        fmt::format("{} light(s) (point, spot, IES, sun, sky) ignored: only the first shot "
                    "(--first-shot) lights voxels from lights",
                    impl_->lights.size()));
  if (scene.hasCoverage())
    s.warnings.push_back(
        "materials that are not opaque (alpha, transmission): the voxel sweeps take a voxel's "
        "surface as opaque where at least half of it is covered and leave it out elsewhere; the "
        "light bounced through partly covered surfaces (Blend, glass) is not carried (the "
        "direct light is: its shadow rays pass them); use --method patch or pathtrace for it");
  s.voxels = impl_->grid.cellCount();
  s.sides = impl_->grid.entryCount();
  s.directions = solution.directions;
  s.laterDirections = solution.laterDirections;
  s.sweepThreads = solution.sweepThreads;
  s.voxelSize = impl_->grid.voxelSize;
  s.visits = solution.cellVisits;
  s.shadowRays = solution.shadowRays;
  s.residuals = solution.residuals;
  s.converged = solution.converged;
  s.tailShare = solution.tailShare;
  s.directSeconds = solution.directSeconds;
  s.sweepSeconds = solution.sweepSeconds;
  s.iterationSeconds = solution.iterationSeconds;
  s.memoryBytes = impl_->grid.memoryBytes() + solution.workingBytes;
  s.resumedIterations = solution.resumedIterations;
  s.warnings.insert(s.warnings.end(), solution.warnings.begin(), solution.warnings.end());
  if (!s.converged && settings.tolerance > 0.0)
    s.warnings.push_back(notConvergedWarning(s, settings, impl_->grid));
}

VoxelRadiosity::VoxelRadiosity(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

VoxelRadiosity::~VoxelRadiosity() = default;
VoxelRadiosity::VoxelRadiosity(VoxelRadiosity&&) noexcept = default;
VoxelRadiosity& VoxelRadiosity::operator=(VoxelRadiosity&&) noexcept = default;

Color VoxelRadiosity::radiance(const SurfaceHit& hit) const {
  const Material& m = impl_->scene->materialOf(hit.triangle);
  if (!hit.frontFace && !m.twoSided) return Color(0.0f);
  const Vec3 n = hit.frontFace ? hit.normal : -hit.normal;
  // The hit's own material and texture, not the voxel's blend: colour edges, emitters and
  // textures stay sharp.
  const Scene& scene = *impl_->scene;
  return impl_->mix.emission(scene, scene.faceOf(hit.triangle).material) *
             scene.textureAt(m.emissionTexture, hit.triangle, hit.barycentric) +
         scene.reflectanceAt(hit.triangle, hit.barycentric) * impl_->field().at(hit.point, n) /
             glm::pi<float>();
}

Color VoxelRadiosity::irradiance(const SurfaceHit& hit) const {
  const Material& m = impl_->scene->materialOf(hit.triangle);
  if (!hit.frontFace && !m.twoSided) return Color(0.0f);
  return impl_->field().at(hit.point, hit.frontFace ? hit.normal : -hit.normal);
}

std::span<const Light> VoxelRadiosity::directLights() const {
  return impl_->mix.lights();
}

std::span<const Color> VoxelRadiosity::emissionScales() const {
  return impl_->mix.emissionScales();
}

std::span<const LightGroup> VoxelRadiosity::lightGroups() const {
  return impl_->mix.groups();
}

std::span<const Color> VoxelRadiosity::groupScales() const {
  return impl_->mix.scales();
}

void VoxelRadiosity::setGroupScales(std::span<const Color> scales) {
  impl_->mix.setScales(scales);
  impl_->combineGroups();
}

Color VoxelRadiosity::groupRadiosity(size_t group, size_t side) const {
  const Impl& m = *impl_;
  const VoxelSurface& s = m.grid.surfaces[m.grid.surface[side]];
  const bool emits = s.emitter != VoxelSurface::kNoEmitter &&
                     m.mix.groupEmission(*m.scene, group, s.emitter) != Color(0.0f);
  const Color e = emits ? glm::pi<float>() * s.material.emission : Color(0.0f);
  return m.mix.scales()[group] * (e + s.material.rho * m.groupIrradiance.at(group)[side]);
}

bool VoxelRadiosity::hasIndirectIrradiance() const {
  return !impl_->indirect.empty();
}

Color VoxelRadiosity::indirectIrradiance(const SurfaceHit& hit) const {
  const Material& m = impl_->scene->materialOf(hit.triangle);
  if (impl_->indirect.empty() || (!hit.frontFace && !m.twoSided)) return Color(0.0f);
  const Vec3 n = hit.frontFace ? hit.normal : -hit.normal;
  return VoxelIrradianceField(impl_->grid, impl_->indirect).at(hit.point, n);
}

const VoxelRadiosityStats& VoxelRadiosity::stats() const {
  return impl_->stats;
}

const Scene& VoxelRadiosity::scene() const {
  return *impl_->scene;
}

size_t VoxelRadiosity::elementCount() const {
  return impl_->grid.entryCount();
}

SurfaceElement VoxelRadiosity::element(size_t e) const {
  const VoxelGrid& grid = impl_->grid;
  const VoxelSurface& surface = grid.surfaces[grid.surface[e]];
  const VoxelMaterial& m = surface.material;
  return {surface.object,
          grid.areaOf(e),
          grid.centroidOf(e),
          grid.unitNormal(e),
          glm::pi<float>() * impl_->emission(e),
          m.rho,
          impl_->solution.irradiance[e],
          impl_->solution.radiosity[e],
          surface.backSide};
}

LitMesh VoxelRadiosity::litMesh() const {
  return bakeSurfaceLight(*impl_->scene, *this, impl_->grid.voxelSize);
}

}  // namespace rad
