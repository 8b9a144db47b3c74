// The Relighter: a patch solution kept up to date by shooting the change of the direct light.
// Its state is a progressive solve part way (ShootingState): what has been shot is exact and the
// unshot radiosity is what is left, so a change of the lights is one more thing left to shoot,
// and nothing is lost between frames: what a relight leaves unshot, the next one shoots.
#include <radiosity/error.h>
#include <radiosity/relighter.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <glm/gtc/constants.hpp>
#include <optional>
#include <stdexcept>
#include <tuple>

#include "lighting/direct_lighting.h"
#include "patch/light_refinement.h"
#include "patch/patch_radiosity_impl.h"
#include "patch/patch_solver_terms.h"
#include "patch/precomputed_transfer.h"

namespace rad {

namespace {

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

bool samePatches(const PatchMesh& a, const PatchMesh& b) {
  if (a.size() != b.size()) return false;
  for (uint32_t p = 0; p < a.size(); ++p)
    if (a.nodeAddress(a.patches()[p].node) != b.nodeAddress(b.patches()[p].node)) return false;
  return true;
}

// A per-patch value of `from` carried to the patches of `to` (both refined from one base mesh):
// each new patch takes the mean of the old patches it overlaps, weighted by the overlap of their
// finest-key ranges (a child takes its parent's value, a parent its children's mean).
std::vector<Color> carryOver(const PatchMesh& from, std::span<const Color> value,
                             const PatchMesh& to, int levels) {
  std::vector<std::tuple<uint64_t, uint64_t, uint32_t>> old(from.size());
  for (uint32_t p = 0; p < from.size(); ++p) {
    const auto [first, last] = from.nodeKeys(from.patches()[p].node, levels);
    old[p] = {first, last, p};
  }
  std::sort(old.begin(), old.end());
  std::vector<Color> out(to.size(), Color(0.0f));
  for (uint32_t q = 0; q < to.size(); ++q) {
    const auto [first, last] = to.nodeKeys(to.patches()[q].node, levels);
    auto it = std::upper_bound(old.begin(), old.end(), std::tuple{first, ~0ull, ~0u});
    if (it != old.begin()) --it;
    Vec3d sum(0.0);
    double weight = 0.0;
    for (; it != old.end() && std::get<0>(*it) < last; ++it) {
      const uint64_t lo = std::max(first, std::get<0>(*it)), hi = std::min(last, std::get<1>(*it));
      if (hi <= lo) continue;
      sum += double(hi - lo) * Vec3d(value[std::get<2>(*it)]);
      weight += double(hi - lo);
    }
    if (weight > 0.0) out[q] = Color(sum / weight);
  }
  return out;
}

// The patches as lights make them: the base mesh refined for them, and their direct light there.
struct LitPatches {
  std::unique_ptr<PatchMesh> mesh;
  std::vector<Color> direct;
};

}  // namespace

struct Relighter::State {
  RelightSettings settings;
  PatchRadiosity current;
  PatchRadiosity::Impl& m;  ///< current's insides
  PatchLightCache cache;
  PatchSystem system;  ///< D: the direct light the state was brought up to
  ShootingState shooting;
  RelightStats stats;
  size_t unsavedRows = 0;  ///< master-table rows cast since the table was read or saved
  /// The mesh's transfer, when the settings ask for it and the mesh never changes.
  std::optional<PrecomputedTransfer> transfer;
  /// Per scene material, the factor on its emission the state holds (empty: none).
  std::vector<Color> emissionScales;

  State(PatchRadiosity solved, const RelightSettings& s)
      : settings(s), current(std::move(solved)), m(*current.impl_) {}

  const FormFactorTable& table() const { return *m.table; }
  void anchor(std::span<const Color> guess);
  LitPatches lightPatches(std::span<const Light> lights, const RayCaster& shadows);
  bool shadowed = false;  ///< the light cache holds values shadowed by objects
  void changeMesh(LitPatches lit);
  void applyDirect(const std::vector<Color>& direct);
  /// E of every patch as the emission scales make it (after m.system(), which has the scene's).
  void scaleEmission();
  /// A change of the emission scales, as more (or less) light to shoot.
  void applyEmission(std::span<const Color> scales);
  void shoot();
  void publish();
};

// The state for radiosities `guess`: one gathering step from it, B = S + rho F guess, with
// H = D + F guess and U = B - guess, which keeps ShootingState's equations exactly.
void Relighter::State::anchor(std::span<const Color> guess) {
  const size_t n = system.size();
  shooting.radiosity.resize(n);
  shooting.irradiance.resize(n);
  shooting.unshot.resize(n);
  tbb::parallel_for(size_t(0), n, [&](size_t i) {
    const Color gathered = gather(table(), i, guess);
    shooting.irradiance[i] = system.directAt(i) + gathered;
    shooting.radiosity[i] = system.source(i) + system.rho[i] * gathered;
    shooting.unshot[i] = shooting.radiosity[i] - guess[i];
  });
}

// The lights' direct light on the patches of a mesh refined for them anew; lights that did not
// change are not evaluated again (the cache).
LitPatches Relighter::State::lightPatches(std::span<const Light> lights, const RayCaster& shadows) {
  m.lights.assign(lights.begin(), lights.end());
  const std::vector<uint8_t> changed = cache.update(m.lights);
  stats.lightsChanged = size_t(std::count(changed.begin(), changed.end(), 1));
  LitPatches lit{std::make_unique<PatchMesh>(*m.model->baseMesh), {}};
  const PatchRadiositySettings& s = m.settings;
  lit.direct = refineForLights(*lit.mesh, DirectLighting(*m.scene, shadows, m.lights),
                               {s.refineLevels, s.refineThreshold, s.lightSamples}, cache)
                   .direct;
  if (lit.direct.empty()) lit.direct.assign(lit.mesh->size(), Color(0.0f));
  return lit;
}

// A new quadtree: its table (the last one updated for the patches that split or merged, their
// rows from the master table), its system, and the state anchored at the old solution carried
// over to the new patches.
void Relighter::State::changeMesh(LitPatches lit) {
  const std::vector<Color> guess =
      carryOver(*m.mesh, m.solution.radiosity, *lit.mesh, m.settings.refineLevels);
  transfer.reset();  // made for the old patches
  const std::unique_ptr<PatchMesh> before = std::move(m.mesh);
  const std::vector<uint32_t> beforeExact = m.ff.exactColumns;
  m.mesh = std::move(lit.mesh);
  m.lightDirect = std::move(lit.direct);
  m.chooseFormFactorSettings();
  m.stats.warnings.clear();
  m.table = m.formFactorsAfter(*before, beforeExact, *m.model->caster);
  stats.rowsComputed = m.stats.rowsComputed;
  stats.rowsReused = m.stats.rowsReused;
  unsavedRows += stats.rowsComputed;
  system = m.system();
  scaleEmission();
  stats.patchesUpdated = m.mesh->size();
  anchor(guess);
}

// Brings the direct light of the patches that changed by more than the threshold up to date, as
// more light (or less) to shoot; smaller changes wait until together they amount to the
// threshold of the light put in.
void Relighter::State::applyDirect(const std::vector<Color>& direct) {
  float brightest = 0.0f;
  for (const Color& d : direct) brightest = std::max(brightest, maxComponent(d));
  const float perPatch = float(settings.threshold) * brightest;
  std::vector<uint32_t> waiting;
  double waitingPower = 0.0;
  auto apply = [&](uint32_t i) {
    const Color change = direct[i] - system.direct[i];
    system.direct[i] = direct[i];
    shooting.irradiance[i] += change;
    shooting.radiosity[i] += system.rho[i] * change;
    shooting.unshot[i] += system.rho[i] * change;
    ++stats.patchesUpdated;
  };
  for (uint32_t i = 0; i < direct.size(); ++i) {
    const Color change = direct[i] - system.direct[i];
    if (change == Color(0.0f)) continue;
    if (maxComponent(glm::abs(change)) > perPatch) {
      apply(i);
    } else {
      waiting.push_back(i);
      waitingPower += double(system.area[i]) * absSum(system.rho[i] * change);
    }
  }
  stats.reanchored = !waiting.empty() && waitingPower > settings.threshold * sourceNorm(system);
  if (stats.reanchored)
    for (uint32_t i : waiting) apply(i);
  else
    stats.patchesSkipped = waiting.size();
}

void Relighter::State::scaleEmission() {
  if (emissionScales.empty()) return;
  for (uint32_t p = 0; p < m.mesh->size(); ++p)
    system.emitted[p] *= emissionScales[m.mesh->patches()[p].material];
}

void Relighter::State::applyEmission(std::span<const Color> scales) {
  const size_t materials = m.scene->materials.size();
  std::vector<Color> next(scales.begin(), scales.end());
  if (next.empty()) next.assign(materials, Color(1.0f));
  if (next.size() != materials)
    throw std::invalid_argument("relight: one emission scale per scene material");
  if (emissionScales.empty()) emissionScales.assign(materials, Color(1.0f));
  if (next == emissionScales) return;
  emissionScales = std::move(next);
  for (uint32_t p = 0; p < m.mesh->size(); ++p) {
    const Patch& patch = m.mesh->patches()[p];
    const uint32_t material = patch.material;
    const Color emitted = glm::pi<float>() * m.scene->materials[material].emission *
                          patch.emissionTint * emissionScales[material];
    const Color change = emitted - system.emitted[p];
    if (change == Color(0.0f)) continue;
    system.emitted[p] = emitted;
    shooting.radiosity[p] += change;
    shooting.unshot[p] += change;
    ++stats.patchesUpdated;
  }
}

// With the transfer, the unshot radiosity bounces out in one step: B += (T - I) U, H += F T U.
void Relighter::State::shoot() {
  const double norm = sourceNorm(system);
  if (norm == 0.0) {
    // No light put in (every light off or dimmed to 0): the answer is no light, exactly, not
    // the last state less its change (shot to a tolerance a zero norm gives no measure of, or
    // through the transfer with its rounding).
    shooting = {sources(system), directIrradiance(system), std::vector<Color>(system.size())};
    stats.shots = 0;
    stats.unshot = 0.0;
    return;
  }
  if (transfer) {
    transfer->propagate(shooting.unshot, table(), shooting.radiosity, shooting.irradiance);
    stats.shots = size_t(std::count_if(shooting.unshot.begin(), shooting.unshot.end(),
                                       [](const Color& u) { return u != Color(0.0f); }));
    std::fill(shooting.unshot.begin(), shooting.unshot.end(), Color(0.0f));
    stats.unshot = 0.0;
    return;
  }
  PatchSolution record;
  shootUnshotInSweeps(table(), system, shooting, norm,
                      {settings.tolerance, m.settings.maxIterations}, record);
  stats.shots = record.shots;
  stats.unshot = record.residuals.back();
}

// The solution the renderers see: the state plus the ambient term for what is left unshot.
void Relighter::State::publish() {
  solutionOf(system, shooting, m.solution);
  // A change shot to a tolerance leaves its residue, of either sign, where the light is near
  // none: the light shown is never below none.
  for (Color& b : m.solution.radiosity) b = glm::max(b, Color(0.0f));
  for (Color& h : m.solution.irradiance) h = glm::max(h, Color(0.0f));
  m.mix.setEmissionScales(emissionScales);  // what radiance() shows of the emitters
  m.lightDirect = system.direct;
  m.indirect = m.indirectOf(m.solution, rowsOf(table()), system);
  for (Color& h : m.indirect) h = glm::max(h, Color(0.0f));
  if (stats.meshChanged) {
    m.hanging = m.mesh->hangingVertices();
    m.recordMesh();
  }
  m.vertexIrradiance = m.averageAtVertices(m.solution.irradiance);
  m.vertexIndirect = m.averageAtVertices(m.indirect);
}

namespace {

void requireMasterTable(const PatchModel::State& model) {
  if (!model.master)
    throw InputError("relighting",
                     "needs the hemisphere form-factor estimator (its master table gives the rows "
                     "of the patches a moved light refines); the model uses another");
}

}  // namespace

Relighter::Relighter(const PatchModel& model, std::span<const Light> lights,
                     const RelightSettings& settings, const ProgressCallback& progress) {
  requireMasterTable(*model.state_);
  auto impl = std::make_unique<PatchRadiosity::Impl>(model.state_, lights);
  impl->keepTable = true;
  impl->saveMaster = false;  // saved once, by saveFormFactors(), not at every quadtree change
  impl->settings.lightGroups = false;  // one state, shot as the lights change
  PatchLightCache cache;
  impl->build(cache, progress);
  start(PatchRadiosity(std::move(impl)), settings);
  state_->cache = std::move(cache);
}

Relighter::Relighter(const PatchModel& model, PatchRadiosity solved,
                     const RelightSettings& settings, const ProgressCallback& progress) {
  requireMasterTable(*model.state_);
  PatchRadiosity::Impl& m = *solved.impl_;
  if (m.model != model.state_)
    throw std::invalid_argument("relighting a solution of another model");
  // One state for all the lights: groups kept apart fold into it only at their own scale.
  for (const Color& scale : m.mix.scales())
    if (scale != Color(1.0f))
      throw InputError("relighting",
                       "the solution's light groups are scaled (--group): relight "
                       "a solution whose groups are at scale 1");
  m.mix = LightGroupMix(*m.scene, m.lights, false);
  m.groupIrradiance.clear();
  m.groupIndirect.clear();
  m.keepTable = true;
  m.saveMaster = false;
  m.chooseFormFactorSettings();
  m.table = m.formFactors(*model.state_->caster, progress);
  start(std::move(solved), settings);  // the light cache starts empty: the first relight fills it
}

void Relighter::start(PatchRadiosity solved, const RelightSettings& settings) {
  state_ = std::make_unique<State>(std::move(solved), settings);
  State& s = *state_;
  s.unsavedRows = s.m.stats.rowsComputed;
  s.system = s.m.system();
  s.anchor(s.m.solution.radiosity);
  s.stats.patches = s.system.size();
  // Only a mesh that no light refines stays the one the transfer was made for.
  if (s.m.settings.refineLevels == 0 && s.system.size() <= settings.transferPatches)
    s.transfer.emplace(s.table(), s.system);
}

Relighter::~Relighter() = default;
Relighter::Relighter(Relighter&&) noexcept = default;
Relighter& Relighter::operator=(Relighter&&) noexcept = default;

const RelightStats& Relighter::relight(std::span<const Light> lights,
                                       std::span<const Color> emissionScales,
                                       const RayCaster* shadowCaster) {
  State& s = *state_;
  const auto start = std::chrono::steady_clock::now();
  s.stats = {};
  s.applyEmission(emissionScales);
  if (shadowCaster || s.shadowed) s.cache.forget();
  s.shadowed = shadowCaster != nullptr;
  LitPatches lit = s.lightPatches(lights, shadowCaster ? *shadowCaster : *s.m.model->caster);
  s.stats.directMs = msSince(start);
  s.stats.meshChanged = !samePatches(*lit.mesh, *s.m.mesh);
  const auto table = std::chrono::steady_clock::now();
  if (s.stats.meshChanged)
    s.changeMesh(std::move(lit));
  else
    s.applyDirect(lit.direct);
  if (s.stats.meshChanged) s.stats.formFactorMs = msSince(table);
  const auto bounce = std::chrono::steady_clock::now();
  s.shoot();
  s.publish();
  s.stats.bounceMs = msSince(bounce);
  s.stats.patches = s.system.size();
  s.stats.milliseconds = msSince(start);
  return s.stats;
}

std::string Relighter::saveFormFactors() {
  State& s = *state_;
  const PatchModel::State& model = *s.m.model;
  if (s.unsavedRows == 0 || model.masterFile.empty()) return {};
  std::string warning = model.master->save(model.masterFile, model.masterKey);
  if (warning.empty()) s.unsavedRows = 0;
  return warning;
}

const PatchRadiosity& Relighter::solution() const {
  return state_->current;
}

const RelightStats& Relighter::lastRelight() const {
  return state_->stats;
}

}  // namespace rad
