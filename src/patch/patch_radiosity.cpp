// The public face of the patch method: mesh, form factors (cached), solve, then answer radiance
// queries by interpolating the irradiance averaged at the welded patch corners.
#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/ray_caster.h>
#include <radiosity/scene_builder.h>
#include <tbb/parallel_for.h>

#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <optional>
#include <unordered_map>

#include "core/convergence_advice.h"
#include "lighting/direct_lighting.h"
#include "lit_mesh/lit_mesh_texturing.h"
#include "patch/form_factor_cache.h"
#include "patch/form_factor_estimators.h"
#include "patch/light_refinement.h"
#include "patch/patch_mesh.h"
#include "patch/patch_model_state.h"
#include "patch/patch_radiosity_impl.h"
#include "patch/patch_solvers.h"
#include "patch/table_update.h"

namespace rad {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void recordRowSums(const std::vector<double>& sums, PatchRadiosityStats& stats) {
  if (sums.empty()) return;
  stats.rowSumMin = *std::min_element(sums.begin(), sums.end());
  stats.rowSumMax = *std::max_element(sums.begin(), sums.end());
  double total = 0.0;
  for (double s : sums) total += s;
  stats.rowSumMean = total / double(sums.size());
}

// How far a row's sum may exceed 1 before it is scaled back: eight times the noise of the sum
// of a row averaged with its column at `rays` rays (1 / (2 sqrt(rays)); rows reach 1.06-1.11 in
// closed scenes at 256 rays, Cornell, room:1 and atrium:2, where the limit is 1.25). A hard
// limit at 1.01 darkened room:1 by 4.5%: it cut the noise's upper half and kept its lower.
// At most what the disk cache accepts, so that it accepts every table it is given.
double rowSumNoise(int rays) {
  return std::min(kMaxCachedRowSum - 1.0, 4.0 / std::sqrt(double(std::max(rays, 1))));
}

// Emitter columns beyond this many (patch, emitter) pairs are left to the hemisphere rays: the
// exact columns cost 16 kernel evaluations a pair, about 1 s per million pairs on 2 cores.
constexpr double kExactColumnPairs = 2e6, kExactPairsPerSecond = 1e6;

}  // namespace

PatchSystem PatchRadiosity::Impl::system() const {
  PatchSystem s;
  for (const Patch& p : mesh->patches()) {
    const Material& m = scene->materials[p.material];
    s.emitted.push_back(glm::pi<float>() * m.emission * p.emissionTint);
    s.rho.push_back(p.rho);
    s.area.push_back(p.coveredArea());
  }
  s.direct = lightDirect.empty() ? std::vector<Color>(mesh->size(), Color(0.0f)) : lightDirect;
  return s;
}

void PatchRadiosity::Impl::chooseFormFactorSettings() {
  ff = {settings.estimator, settings.formFactorRays, settings.seed, {}, settings.processes};
  emitterRows.assign(mesh->size(), 0);
  for (uint32_t p = 0; p < mesh->size(); ++p)
    emitterRows[p] = scene->materials[mesh->patches()[p].material].emits();
  // The hemisphere estimator takes the emitters' columns exactly (ExactColumns), while they are
  // few: large emitters are found by enough of every patch's rays anyway.
  if (settings.estimator != PatchFormFactorEstimator::Hemisphere) return;
  for (uint32_t p = 0; p < mesh->size(); ++p)
    if (emitterRows[p]) ff.exactColumns.push_back(p);
  const double pairs = double(ff.exactColumns.size()) * double(mesh->size());
  if (pairs > kExactColumnPairs) {
    stats.warnings.push_back(fmt::format(
        "direct light from {} emitter patches by hemisphere rays alone (exact, its {:.3g} "
        "patch-emitter pairs would take about {:.0f} s): expect it to vary from patch to patch; "
        "fewer patches make it exact",
        ff.exactColumns.size(), pairs, pairs / kExactPairsPerSecond));
    ff.exactColumns.clear();
  }
  stats.exactColumns = ff.exactColumns.size();
}

// The estimators that integrate toward a patch's polygon (exact, pairwise, the emitters' exact
// columns) take its mean coverage, as if a cut-out's holes were spread evenly over it.
void PatchRadiosity::Impl::warnOfCutOutTargets() {
  bool cutOut = false;
  for (uint32_t t = 0; t < scene->triangles.size() && !cutOut; ++t)
    cutOut = !scene->uniformCoverage(t);
  if (!cutOut ||
      (settings.estimator == PatchFormFactorEstimator::Hemisphere && ff.exactColumns.empty()))
    return;
  stats.warnings.push_back(
      "cut-out materials (alpha from a texture or vertex colours): form factors toward a patch "
      "by its polygon (the exact and pairwise estimators, the emitters' exact columns) take its "
      "mean coverage, its holes as if spread evenly over it; smaller patches resolve them");
}

// Rows to table: pairwise estimates are reciprocal by construction; the others average both
// directions. Rows past 1 are scaled back: estimates of a patch far larger than the emitter
// beside it (the exact columns' reciprocity multiplies a 16-point estimate by A_i / A_j) made
// the light of a real atrium's lamps 1.5 to 2 times what they emit. Then the threshold.
FormFactorTable PatchRadiosity::Impl::assembleTable(FormFactorRows rows) {
  FormFactorTable table = FormFactorTable::fromRows(std::move(rows));
  std::vector<float> area;
  for (const Patch& p : mesh->patches()) area.push_back(p.coveredArea());
  if (settings.estimator != PatchFormFactorEstimator::Pairwise) table.symmetrize(area);
  closeTable(table);
  table.applyThreshold(area, settings.formFactorThreshold, emitterRows);
  tableSymmetrizedOnly = tableSymmetrizedOnly && !(settings.formFactorThreshold > 0.0f);
  return table;
}

void PatchRadiosity::Impl::closeTable(FormFactorTable& table) {
  const FormFactorTable::ClosureRepair closure = table.closeRows(rowSumNoise(ff.rays));
  stats.rowsScaledToClosure = closure.rows;
  stats.rowSumEstimatedMax = closure.worstSum;
  tableSymmetrizedOnly = closure.rows == 0;
}

// The noise's allowance past closure (rowSumNoise) stops where a patch's light would come back
// from one bounce stronger than it left: with rho 0.999 (a glTF interior whose textures went
// missing) rows of 1.06 made the Gauss-Seidel residual rise from sweep 193 on, to 0.35 after
// 1,000 sweeps. A thresholded table's rows may sum far past 1 (a small patch gathering what
// large ones send it) and keep the power each patch sends: its shares are what count.
void PatchRadiosity::Impl::boundReflection(FormFactorTable& table) {
  std::vector<float> rho(mesh->size()), area(mesh->size());
  for (uint32_t p = 0; p < mesh->size(); ++p) {
    rho[p] = maxComponent(mesh->patches()[p].rho);
    area[p] = mesh->patches()[p].coveredArea();  // the areas reciprocity holds in
  }
  const FormFactorTable::ReflectionBound bound = table.boundReflection(rho, area, kMaxReflectance);
  stats.scaledForReflection = bound.patches;
  stats.reflectedShareMax = bound.worstShare;
  tableSymmetrizedOnly = tableSymmetrizedOnly && bound.patches == 0;
}

// The table for this mesh, and its numbers in the stats.
FormFactorTable PatchRadiosity::Impl::formFactors(const RayCaster& caster,
                                                  const ProgressCallback& progress) {
  FormFactorTable table = loadOrComputeFormFactors(caster, progress);
  boundReflection(table);
  recordTable(table);
  return table;
}

void PatchRadiosity::Impl::recordTable(const FormFactorTable& table) {
  stats.nonZeros = table.nonZeros();
  stats.tableBytes = table.memoryBytes();
  recordThresholdLoss(table.thresholdLoss());
  std::vector<double> sums(table.rows());
  tbb::parallel_for(size_t(0), sums.size(), [&](size_t i) { sums[i] = table.rowSum(i); });
  recordRowSums(sums, stats);
}

FormFactorTable PatchRadiosity::Impl::formFactorsAfter(const PatchMesh& before,
                                                       std::span<const uint32_t> beforeExact,
                                                       const RayCaster& caster) {
  if (!model->master || !table || !tableSymmetrizedOnly) return formFactors(caster, {});
  const auto start = std::chrono::steady_clock::now();
  const int levels = model->master->levels();
  std::optional<PatchMatch> match = matchPatches(before, *mesh, levels);
  if (!match) return formFactors(caster, {});
  const MasterFormFactorTable::Rows rows =
      model->master->rowsFor(*mesh, caster, model->basePatchOf, ff, {}, match->fresh());
  std::optional<FormFactorTable> updated =
      updatedTable({before, *table, beforeExact}, *mesh, std::move(*match), ff.exactColumns, rows,
                   levels, spareTable ? std::move(*spareTable) : FormFactorTable{});
  spareTable.reset();
  if (!updated) return formFactors(caster, {});
  // Kept for the next change, unless large: it saves the page faults of a new table (4 ms of
  // a relight's 80 at 16k patches), which matter at frame rate, not for tables that take
  // seconds to update.
  constexpr size_t kSpareTableBytes = size_t(256) << 20;
  if (table->memoryBytes() <= kSpareTableBytes) spareTable = std::move(*table);
  closeTable(*updated);
  boundReflection(*updated);
  stats.rowsComputed = rows.computed;
  stats.rowsReused = mesh->size() - rows.computed;
  stats.masterRows = model->master->rows();
  stats.formFactorSeconds = secondsSince(start);
  recordTable(*updated);
  return std::move(*updated);
}

// The hemisphere estimator's table from the model's master table (rows kept by node, cast only
// for nodes never solved before, saved to the disk cache when it grew); the other estimators'
// from the disk cache of whole tables, else computed.
FormFactorTable PatchRadiosity::Impl::loadOrComputeFormFactors(const RayCaster& caster,
                                                               const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  if (model->master) {
    MasterFormFactorTable::Rows rows =
        model->master->rowsFor(*mesh, caster, model->basePatchOf, ff, progress);
    stats.rowsComputed = rows.computed;
    stats.rowsReused = rows.reused;
    stats.masterRows = model->master->rows();
    stats.cacheLoaded = model->masterLoaded;
    stats.cacheFile = model->masterFile.string();
    if (!model->masterWarning.empty()) stats.warnings.push_back(model->masterWarning);
    FormFactorTable table = assembleTable(std::move(rows.rows));
    stats.formFactorSeconds = secondsSince(start);
    if (saveMaster && rows.computed > 0 && !model->masterFile.empty())
      if (std::string w = model->master->save(model->masterFile, model->masterKey); !w.empty())
        stats.warnings.push_back(w);
    return table;
  }
  const FormFactorCacheKey key =
      formFactorCacheKey(*scene, *mesh, ff, settings.formFactorThreshold);
  std::filesystem::path file;
  if (!settings.cacheDir.empty()) {
    file = formFactorCacheFile(settings.cacheDir, key);
    stats.cacheFile = file.string();
    FormFactorCacheLoad load = loadFormFactorTable(file, key, mesh->size());
    if (!load.warning.empty()) stats.warnings.push_back(load.warning);
    if (load.table) {
      stats.cacheLoaded = true;
      stats.cacheLoadSeconds = secondsSince(start);
      return std::move(*load.table);
    }
  }
  FormFactorTable table = assembleTable(estimateFormFactors(*mesh, caster, ff, progress));
  stats.formFactorSeconds = secondsSince(start);
  stats.rowsComputed = mesh->size();
  if (!file.empty())
    if (std::string w = saveFormFactorTable(file, key, table); !w.empty())
      stats.warnings.push_back(w);
  return table;
}

// The analytic lights' direct light on the patches, refining the mesh where it changes fast.
void PatchRadiosity::Impl::lightPatches(const RayCaster& caster, PatchLightCache& cache,
                                        const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  const uint64_t raysBefore = caster.raysCast();
  LightRefinement refined = refineForLights(
      *mesh, DirectLighting(*scene, caster, lights),
      {settings.refineLevels, settings.refineThreshold, settings.lightSamples}, cache, progress);
  lightDirect = std::move(refined.direct);
  for (size_t g = 0; g < mix.groups().size() && !lightDirect.empty(); ++g)
    groupDirect.push_back(cache.directOf(*mesh, mix.groups()[g].lights));
  stats.basePatches = refined.basePatches;
  stats.refinedSplits = refined.split;
  stats.refineRounds = refined.rounds;
  stats.lightRays = caster.raysCast() - raysBefore;
  stats.lightSeconds = secondsSince(start);
}

void PatchRadiosity::Impl::recordThresholdLoss(const ThresholdLoss& loss) {
  stats.droppedEntryFraction = loss.entryFraction;
  stats.droppedSumFraction = loss.sumFraction;
  stats.droppedWorstRowFraction = loss.worstRowFraction;
  stats.rowsDroppingOverOnePercent = loss.rowsOverOnePercent;
}

// The kept entries carry the dropped ones' light (thresholdRow), so energy balances; but light
// then goes to the wrong places where a row lost much of its sum.
void PatchRadiosity::Impl::warnOfThresholdLoss() {
  if (stats.rowsDroppingOverOnePercent == 0) return;
  stats.warnings.push_back(fmt::format(
      "--ff-threshold {} dropped more than 1% of the form-factor sum of {} of {} patches (up to "
      "{:.1f}%, {:.1f}% of all): their kept entries were scaled up to keep the light, which moves "
      "the bounce light toward the patches they see most; a lower threshold keeps it where it "
      "falls",
      settings.formFactorThreshold, stats.rowsDroppingOverOnePercent, mesh->size(),
      100.0 * stats.droppedWorstRowFraction, 100.0 * stats.droppedSumFraction));
}

// The bound keeps the solve from growing, but the light the noise put past closure is lost:
// with rho near 1 the answer hangs on closure to 1 / (1 - rho) times the rays' noise (a closed
// box of rho 0.999 at 256 rays: rows of 0.88-1.10, mean 1.0001 diverged; bound, mean 0.981).
void PatchRadiosity::Impl::warnOfReflectionBound() {
  if (stats.scaledForReflection == 0) return;
  float rhoMax = 0.0f;
  for (const Patch& p : mesh->patches()) rhoMax = std::max(rhoMax, maxComponent(p.rho));
  stats.warnings.push_back(fmt::format(
      "{} of {} patches sent on more light than reached them (reflected share up to {:.3f}: "
      "reflectance up to {:.3f} and form-factor rows past 1 by the rays' noise), scaled back to "
      "{} so that the solve cannot grow; the light past closure is lost there: expect the scene "
      "darker than its reflectances say (more --ff-rays close the rows better; a texture lost on "
      "import leaves a material at its factor, often 1)",
      stats.scaledForReflection, mesh->size(), stats.reflectedShareMax, rhoMax, kMaxReflectance));
}

// Ended above the tolerance: the answer is short of light still bouncing, or, diverging, holds
// light the table made. The warning gives the numbers and what to change; at the last sweeps'
// rate of fall, how many more sweeps the tolerance wants.
void PatchRadiosity::Impl::reportConvergence() {
  stats.converged = solution.converged;
  stats.diverging = solution.diverging;
  if (solution.converged || solution.residuals.empty()) return;
  const std::vector<double>& r = solution.residuals;
  const std::string solver(choiceName(kPatchSolverNames, settings.solver));
  const std::string sweeps = settings.solver == PatchSolverKind::Progressive
                                 ? "rounds of shots (one shot a patch)"
                                 : solver + " sweeps";
  if (solution.diverging) {
    stats.warnings.push_back(fmt::format(
        "patch solve diverging: its residual rose {} sweeps in a row, to {:.3g} after {} {} "
        "(lowest {:.3g}; --tolerance {:g}), so it stopped: the form factors send on more light "
        "than they gather somewhere; more --ff-rays or another --ff-estimator may hold it",
        kRisingSweeps, r.back(), solution.iterations, sweeps, *std::min_element(r.begin(), r.end()),
        settings.tolerance));
    return;
  }
  float rhoMax = 0.0f;
  for (const Patch& p : mesh->patches()) rhoMax = std::max(rhoMax, maxComponent(p.rho));
  stats.warnings.push_back(fmt::format(
      "patch solve not converged: residual {:.3g} after {} {} (--max-iterations {}), above "
      "--tolerance {:g}; raise --max-iterations{} or --tolerance{}",
      r.back(), solution.iterations, sweeps, settings.maxIterations, settings.tolerance,
      remainingStepsAdvice(r, settings.tolerance, "sweep"), nearWhiteAdvice(rhoMax)));
}

// A row computed alone (not made reciprocal) past 1 + noise, scaled back to 1, as closeRows does,
// then past its reflected share, scaled back to kMaxReflectance, as boundReflection does.
void PatchRadiosity::Impl::closeRow(std::vector<FormFactorEntry>& row) {
  double sum = 0.0;
  for (const FormFactorEntry& e : row) sum += e.value;
  stats.rowSumEstimatedMax = std::max(stats.rowSumEstimatedMax, sum);
  if (sum > 1.0 + rowSumNoise(ff.rays)) {
    for (FormFactorEntry& e : row) e.value = float(e.value / sum);
    ++stats.rowsScaledToClosure;
  }
  // Shooting reads row i as where i's light goes: the share of it reflected is sum_j rho_j F_ij.
  double share = 0.0;
  for (const FormFactorEntry& e : row)
    share += double(maxComponent(mesh->patches()[e.column].rho)) * e.value;
  stats.reflectedShareMax = std::max(stats.reflectedShareMax, share);
  if (!(share > kMaxReflectance)) return;
  for (FormFactorEntry& e : row) e.value = float(e.value * (kMaxReflectance / share));
  ++stats.scaledForReflection;
}

void PatchRadiosity::Impl::solveLazily(const RayCaster& caster, const PatchSystem& system,
                                       const ProgressCallback& progress) {
  std::vector<std::vector<uint32_t>> columns(mesh->size());
  std::vector<std::vector<float>> values(mesh->size());
  std::vector<double> sums;
  const auto start = std::chrono::steady_clock::now();
  const std::optional<ExactColumns> exact = exactColumns(*mesh, caster, ff);
  stats.formFactorSeconds += secondsSince(start);
  std::vector<RowThresholding> thresholded;
  auto row = [&](uint32_t i) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<FormFactorEntry> entries =
        hemisphereRow(*mesh, caster, i, ff.rays, ff.seed, exact ? &*exact : nullptr);
    closeRow(entries);
    const RowThresholding rowSums =
        thresholdRow(entries, emitterRows[i] ? 0.0f : settings.formFactorThreshold);
    thresholded.push_back(rowSums);
    for (const FormFactorEntry& e : entries) {
      columns[i].push_back(e.column);
      values[i].push_back(e.value);
    }
    sums.push_back(rowSums.total);
    stats.nonZeros += values[i].size();
    stats.tableBytes += values[i].size() * (sizeof(uint32_t) + sizeof(float));
    stats.formFactorSeconds += secondsSince(start);
    return FormFactorRowView{columns[i], values[i]};
  };
  std::vector<uint8_t> done(mesh->size(), 0);
  const FormFactorRowSource rowOf = [&](uint32_t i) {
    if (!done[i]) {
      done[i] = 1;
      return row(i);
    }
    return FormFactorRowView{columns[i], values[i]};
  };
  solution =
      solveProgressive(rowOf, system, {settings.tolerance, settings.maxIterations}, progress);
  indirect = indirectOf(solution, rowOf, system);
  recordRowSums(sums, stats);
  recordThresholdLoss(lossOf(thresholded));
  solution.seconds -= stats.formFactorSeconds;  // the solver's time, without the rows' rays
}

void PatchRadiosity::Impl::solve(const RayCaster& caster, const ProgressCallback& progress) {
  const PatchSystem system = this->system();
  chooseFormFactorSettings();
  warnOfCutOutTargets();
  const bool lazy = settings.solver == PatchSolverKind::Progressive &&
                    settings.estimator == PatchFormFactorEstimator::Hemisphere &&
                    settings.cacheDir.empty() && !keepTable && !mix.apart();
  if (lazy) return solveLazily(caster, system, progress);
  FormFactorTable table = formFactors(caster, progress);
  if (mix.apart()) {
    solveGroups(table, progress);
  } else {
    solution = solveSystem(table, system, progress);
    indirect = indirectOf(solution, rowsOf(table), system);
  }
  if (keepTable) this->table = std::move(table);
}

PatchSolution PatchRadiosity::Impl::solveSystem(const FormFactorTable& table,
                                                const PatchSystem& system,
                                                const ProgressCallback& progress) const {
  const PatchSolverControl control{settings.tolerance, settings.maxIterations, &settings.processes};
  switch (settings.solver) {
    case PatchSolverKind::Jacobi:
      return solveJacobi(table, system, control, progress);
    case PatchSolverKind::GaussSeidel:
      return solveGaussSeidel(table, system, control, progress);
    case PatchSolverKind::Progressive:
      break;
  }
  return solveProgressive(rowsOf(table), system, control, progress);
}

// Each group's emitters alone: its materials' E (the others' zero) and its lights' D. The
// solution's iterations, shots and residuals are the groups' together, in group order.
void PatchRadiosity::Impl::solveGroups(const FormFactorTable& table,
                                       const ProgressCallback& progress) {
  const PatchSystem all = system();
  groupIrradiance.clear();
  groupIndirect.clear();
  solution = {};
  solution.converged = true;
  for (size_t g = 0; g < mix.groups().size(); ++g) {
    PatchSystem s = all;
    for (uint32_t p = 0; p < mesh->size(); ++p)
      s.emitted[p] = glm::pi<float>() * mix.groupEmission(*scene, g, mesh->patches()[p].material);
    s.direct = groupDirect.empty() ? std::vector<Color>(mesh->size(), Color(0.0f)) : groupDirect[g];
    PatchSolution solved = solveSystem(table, s, progressPart(progress, g, mix.groups().size()));
    groupIndirect.push_back(indirectOf(solved, rowsOf(table), s));
    groupIrradiance.push_back(std::move(solved.irradiance));
    solution.iterations += solved.iterations;
    solution.shots += solved.shots;
    solution.seconds += solved.seconds;
    solution.residuals.insert(solution.residuals.end(), solved.residuals.begin(),
                              solved.residuals.end());
    solution.converged = solution.converged && solved.converged;
    solution.diverging = solution.diverging || solved.diverging;
  }
  groupDirect.clear();
  combineGroups();
}

void PatchRadiosity::Impl::combineGroups() {
  solution.irradiance = mix.combine(groupIrradiance);
  indirect = mix.combine(groupIndirect);
  solution.emitted.resize(mesh->size());
  solution.radiosity.resize(mesh->size());
  for (uint32_t p = 0; p < mesh->size(); ++p) {
    const Patch& patch = mesh->patches()[p];
    solution.emitted[p] =
        glm::pi<float>() * mix.emission(*scene, patch.material) * patch.emissionTint;
    solution.radiosity[p] = solution.emitted[p] + patch.rho * solution.irradiance[p];
  }
}

// What bounced at least once: H less D and less what the emitters send directly, sum over
// emitting j of E_j F_ji A_j / A_i (row j read as where j's light goes, as shooting reads it).
std::vector<Color> PatchRadiosity::Impl::indirectOf(const PatchSolution& solved,
                                                    const FormFactorRowSource& rows,
                                                    const PatchSystem& system) const {
  std::vector<Vec3d> h(system.size());
  for (size_t i = 0; i < h.size(); ++i)
    h[i] = Vec3d(solved.irradiance[i]) - Vec3d(system.directAt(i));
  for (uint32_t j = 0; j < system.size(); ++j) {
    if (maxComponent(system.emitted[j]) <= 0.0f) continue;
    const FormFactorRowView row = rows(j);
    for (size_t k = 0; k < row.columns.size(); ++k) {
      const uint32_t i = row.columns[k];
      h[i] -= Vec3d(system.emitted[j]) * (double(row.values[k]) * system.area[j] / system.area[i]);
    }
  }
  std::vector<Color> out(h.size());
  for (size_t i = 0; i < h.size(); ++i) out[i] = Color(glm::max(h[i], Vec3d(0.0)));
  return out;
}

std::vector<Color> PatchRadiosity::Impl::averageAtVertices(
    const std::vector<Color>& perPatch) const {
  std::vector<Color> atVertex(mesh->vertices().size(), Color(0.0f));
  std::vector<float> weight(mesh->vertices().size(), 0.0f);
  for (uint32_t p = 0; p < mesh->size(); ++p) {
    const PatchNode& node = mesh->nodeOf(p);
    const float a = mesh->patches()[p].coveredArea();
    for (int k = 0; k < node.cornerCount(); ++k) {
      atVertex[node.corners[k]] += a * perPatch[p];
      weight[node.corners[k]] += a;
    }
  }
  for (size_t v = 0; v < weight.size(); ++v)
    if (weight[v] > 0.0f) atVertex[v] /= weight[v];
  // Where a fine patch meets a coarse one, the coarse patch interpolates its edge between its
  // corners: the fine side's vertex on that edge takes the same value, or the shading cracks.
  for (const HangingVertex& h : hanging)
    atVertex[h.vertex] = 0.5f * (atVertex[h.a] + atVertex[h.b]);
  return atVertex;
}

PatchRadiosity::PatchRadiosity(const Scene& scene, const PatchRadiositySettings& settings,
                               const ProgressCallback& progress)
    : PatchRadiosity(PatchModel(scene, settings).solve(scene.lights, progress)) {}

PatchRadiosity::Impl::Impl(std::shared_ptr<const PatchModel::State> m, std::span<const Light> l)
    : model(std::move(m)),
      scene(model->scene),
      settings(model->settings),
      lights(l.begin(), l.end()),
      mesh(std::make_unique<PatchMesh>(*model->baseMesh)) {
  stats.meshSeconds = model->meshSeconds;
}

void PatchRadiosity::Impl::build(PatchLightCache& cache, const ProgressCallback& progress) {
  const RayCaster& caster = *model->caster;
  const uint64_t raysBefore = caster.raysCast();
  mix = LightGroupMix(*scene, lights, settings.lightGroups);
  cache.update(lights);
  lightPatches(shadowCaster ? *shadowCaster : caster, cache, progress);
  shadowCaster = nullptr;  // only for this solve
  solve(caster, progress);
  warnOfThresholdLoss();
  warnOfReflectionBound();
  reportConvergence();
  shadeVertices();
  recordMesh();
  stats.solveSeconds = solution.seconds;
  stats.rays = caster.raysCast() - raysBefore;
  stats.solver = choiceName(kPatchSolverNames, settings.solver);
  stats.iterations = solution.iterations;
  stats.shots = solution.shots;
  stats.residuals = solution.residuals;
}

void PatchRadiosity::Impl::shadeVertices() {
  hanging = mesh->hangingVertices();
  vertexIrradiance = averageAtVertices(solution.irradiance);
  vertexIndirect = averageAtVertices(indirect);
}

void PatchRadiosity::Impl::recordMesh() {
  stats.patches = mesh->size();
  stats.nodes = mesh->nodes().size();
  stats.vertices = mesh->vertices().size();
  stats.patchSize = mesh->patchSize();
  stats.memoryBytes = mesh->memoryBytes() + stats.tableBytes +
                      solution.radiosity.size() * 4 * sizeof(Color) +
                      (model->master ? model->master->memoryBytes() : 0);
}

PatchRadiosity::PatchRadiosity(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

PatchRadiosity::PatchRadiosity(std::shared_ptr<const PatchModel::State> model,
                               std::span<const Light> lights, const RayCaster* shadowCaster,
                               const ProgressCallback& progress)
    : impl_(std::make_unique<Impl>(std::move(model), lights)) {
  impl_->shadowCaster = shadowCaster;
  PatchLightCache cache;
  impl_->build(cache, progress);
}

std::span<const Light> PatchRadiosity::directLights() const {
  return impl_->mix.apart() ? impl_->mix.lights() : std::span<const Light>(impl_->lights);
}

std::span<const Color> PatchRadiosity::emissionScales() const {
  return impl_->mix.emissionScales();
}

std::span<const LightGroup> PatchRadiosity::lightGroups() const {
  return impl_->mix.groups();
}

std::span<const Color> PatchRadiosity::groupScales() const {
  return impl_->mix.scales();
}

void PatchRadiosity::setGroupScales(std::span<const Color> scales) {
  impl_->mix.setScales(scales);
  impl_->combineGroups();
  impl_->shadeVertices();
}

Color PatchRadiosity::groupRadiosity(size_t group, size_t p) const {
  const Impl& m = *impl_;
  const Patch& patch = m.mesh->patches()[p];
  const Color e =
      glm::pi<float>() * m.mix.groupEmission(*m.scene, group, patch.material) * patch.emissionTint;
  return m.mix.scales()[group] * (e + patch.rho * m.groupIrradiance.at(group)[p]);
}

PatchRadiosity::~PatchRadiosity() = default;
PatchRadiosity::PatchRadiosity(PatchRadiosity&&) noexcept = default;
PatchRadiosity& PatchRadiosity::operator=(PatchRadiosity&&) noexcept = default;

std::optional<Color> PatchRadiosity::Impl::interpolate(const SurfaceHit& hit,
                                                       const std::vector<Color>& perPatch,
                                                       const std::vector<Color>& perVertex) const {
  const PatchMesh::Location loc = mesh->locate(hit.triangle, hit.frontFace, hit.point);
  if (loc.patch == kNoPatch) return std::nullopt;
  if (settings.shading == PatchShading::Flat) return perPatch[loc.patch];
  const PatchNode& node = mesh->nodeOf(loc.patch);
  Color h(0.0f);
  for (int k = 0; k < node.cornerCount(); ++k) h += loc.weights[k] * perVertex[node.corners[k]];
  return h;
}

Color PatchRadiosity::radiance(const SurfaceHit& hit) const {
  const Material& m = impl_->scene->materialOf(hit.triangle);
  if (!hit.frontFace && !m.twoSided) return Color(0.0f);
  const std::optional<Color> h =
      impl_->interpolate(hit, impl_->solution.irradiance, impl_->vertexIrradiance);
  if (!h) return Color(0.0f);
  // The hit's own material and texture: colour edges, emitters and textures stay sharp (a
  // lightmap's way: the irradiance smooth, the albedo per pixel).
  const Scene& scene = *impl_->scene;
  return impl_->mix.emission(scene, scene.faceOf(hit.triangle).material) *
             scene.textureAt(m.emissionTexture, hit.triangle, hit.barycentric) +
         scene.reflectanceAt(hit.triangle, hit.barycentric) * *h / glm::pi<float>();
}

Color PatchRadiosity::irradiance(const SurfaceHit& hit) const {
  const Material& m = impl_->scene->materialOf(hit.triangle);
  if (!hit.frontFace && !m.twoSided) return Color(0.0f);
  return impl_->interpolate(hit, impl_->solution.irradiance, impl_->vertexIrradiance)
      .value_or(Color(0.0f));
}

Color PatchRadiosity::indirectIrradiance(const SurfaceHit& hit) const {
  const Material& m = impl_->scene->materialOf(hit.triangle);
  if (!hit.frontFace && !m.twoSided) return Color(0.0f);
  return impl_->interpolate(hit, impl_->indirect, impl_->vertexIndirect).value_or(Color(0.0f));
}

const PatchRadiosityStats& PatchRadiosity::stats() const {
  return impl_->stats;
}

const Scene& PatchRadiosity::scene() const {
  return *impl_->scene;
}

size_t PatchRadiosity::elementCount() const {
  return impl_->mesh->size();
}

SurfaceElement PatchRadiosity::element(size_t p) const {
  const Impl& m = *impl_;
  const Patch& patch = m.mesh->patches()[p];
  return {patch.object,
          patch.coveredArea(),
          patch.centroid,
          patch.normal,
          m.solution.emitted[p],
          patch.rho,
          m.solution.irradiance[p],
          m.solution.radiosity[p],
          m.mesh->roots()[m.mesh->nodeOf(uint32_t(p)).root].back};
}

// The mesh a viewer sees: what radiance() returns, baked into vertex colours. Smooth shading
// shares a vertex between the patches welded there, but only within one object and material
// (radiance() uses the hit's own material, so colour edges and emitters stay sharp); flat shading
// gives every patch its own corners. A two-sided face's mirrored back patches are written too,
// with the back's own light: glTF culls the side a one-sided triangle turns away, so each side
// shows its own.
LitMesh PatchRadiosity::litMesh() const {
  return impl_->litMesh();
}

LitMesh PatchRadiosity::Impl::litMesh() const {
  const bool smooth = settings.shading == PatchShading::Smooth;
  std::vector<std::vector<uint32_t>> byObject(scene->objects.size());
  for (uint32_t p = 0; p < mesh->size(); ++p) byObject[mesh->patches()[p].object].push_back(p);
  // A coarse patch next to finer ones takes their vertices on its edges into its outline, so the
  // mesh has no T-junctions (no cracks where a viewer rasterizes it).
  std::unordered_map<uint64_t, uint32_t> midpointOf;
  auto edgeKey = [](uint32_t a, uint32_t b) {
    return (uint64_t(std::min(a, b)) << 32) | std::max(a, b);
  };
  for (const HangingVertex& h : hanging) midpointOf[edgeKey(h.a, h.b)] = h.vertex;
  // The vertices strictly inside the edge from a to b, in order.
  auto inside = [&](auto&& self, uint32_t a, uint32_t b, std::vector<uint32_t>& out) -> void {
    const auto it = midpointOf.find(edgeKey(a, b));
    if (it == midpointOf.end()) return;
    self(self, a, it->second, out);
    out.push_back(it->second);
    self(self, it->second, b, out);
  };

  LitMesh out;
  LitMeshTexturing texturing(*scene, out);
  // (vertex, material) -> index, per object; a textured patch's by (vertex, face), the face
  // marked by the top bit: its coordinates are its face's.
  std::unordered_map<uint64_t, uint32_t> vertexOf;
  constexpr uint64_t kFaceKey = uint64_t(1) << 31;
  std::vector<uint32_t> outline, onEdges, index;
  // What a vertex of a patch shows: the outgoing radiance, or under a texture H / pi.
  auto colourOf = [&](const Patch& patch, const Color& h, bool textured) {
    if (textured) return h / glm::pi<float>();
    return mix.emission(*scene, patch.material) * patch.emissionTint +
           patch.rho * h / glm::pi<float>();
  };
  for (uint32_t o = 0; o < byObject.size(); ++o) {
    vertexOf.clear();
    const uint32_t firstTriangle = uint32_t(out.indices.size() / 3);
    for (uint32_t p : byObject[o]) {
      const Patch& patch = mesh->patches()[p];
      const PatchNode& node = mesh->nodeOf(p);
      const int n = node.cornerCount();
      const bool textured = texturing.textured(patch.material);
      const uint32_t trianglesBefore = uint32_t(out.indices.size() / 3);
      outline.clear();
      onEdges.clear();  // per outline point: a bit for each patch edge it lies on
      for (int k = 0; k < n; ++k) {
        outline.push_back(node.corners[k]);
        onEdges.push_back((1u << k) | (1u << ((k + n - 1) % n)));
        inside(inside, node.corners[k], node.corners[(k + 1) % n], outline);
        onEdges.resize(outline.size(), 1u << k);
      }
      index.clear();
      for (const uint32_t v : outline) {
        index.push_back(uint32_t(out.positions.size()));
        if (smooth) {
          const uint64_t key =
              (uint64_t(v) << 32) | (textured ? kFaceKey | patch.face : patch.material);
          const auto [it, added] = vertexOf.try_emplace(key, index.back());
          index.back() = it->second;
          if (!added) continue;
        }
        const Color h = smooth ? vertexIrradiance[v] : solution.irradiance[p];
        out.positions.push_back(mesh->vertices()[v]);
        out.normals.push_back(smooth ? mesh->vertexNormals()[v] : patch.normal);
        out.colors.push_back(colourOf(patch, h, textured));
        texturing.addVertex(textured ? texturing.texcoordOnFace(patch.face, mesh->vertices()[v])
                                     : Vec2(0.0f));
      }
      // The outline is CCW about the side's normal, so fans keep the front facing out. A fan
      // from a corner whose two edges hold no finer vertices (then no triangle is flat), else
      // from a vertex at the centre (the corners' mean, as radiance() interpolates it there).
      size_t apex = outline.size();
      for (size_t i = 0; i < outline.size() && apex == outline.size(); ++i) {
        const size_t next = (i + 1) % outline.size(),
                     prev = (i + outline.size() - 1) % outline.size();
        const bool corner = std::popcount(onEdges[i]) == 2;
        if (corner && std::popcount(onEdges[next]) == 2 && std::popcount(onEdges[prev]) == 2)
          apex = i;
      }
      if (apex < outline.size()) {
        for (size_t t = 1; t + 1 < outline.size(); ++t)
          out.indices.insert(out.indices.end(), {index[apex], index[(apex + t) % outline.size()],
                                                 index[(apex + t + 1) % outline.size()]});
        for (uint32_t t = trianglesBefore; t < out.indices.size() / 3; ++t)
          texturing.addTriangle(patch.material);
        continue;
      }
      const uint32_t centre = uint32_t(out.positions.size());
      Vec3 position(0.0f), normal(0.0f);
      Color colour(0.0f);
      for (int k = 0; k < n; ++k) {
        position += mesh->vertices()[node.corners[k]] / float(n);
        normal += mesh->vertexNormals()[node.corners[k]];
        colour += (smooth ? vertexIrradiance[node.corners[k]] : solution.irradiance[p]) / float(n);
      }
      out.positions.push_back(position);
      out.normals.push_back(smooth ? glm::normalize(normal) : patch.normal);
      out.colors.push_back(colourOf(patch, colour, textured));
      texturing.addVertex(textured ? texturing.texcoordOnFace(patch.face, position) : Vec2(0.0f));
      for (size_t t = 0; t < outline.size(); ++t) {
        out.indices.insert(out.indices.end(), {centre, index[t], index[(t + 1) % outline.size()]});
        texturing.addTriangle(patch.material);
      }
    }
    out.groups.push_back(
        {scene->objects[o].name, firstTriangle, uint32_t(out.indices.size() / 3) - firstTriangle});
  }
  return out;
}

std::string defaultPatchCacheDir() {
  return defaultFormFactorCacheDir().string();
}

}  // namespace rad
