// The one registry of methods (radiosity_method.h) and the settings table it makes: the general
// settings and every registered method's own (solver_settings.h).
#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/radiosity_method.h>

#include <algorithm>
#include <mutex>
#include <stdexcept>

#include "patch/patch_method.h"
#include "render/path_tracer_method.h"
#include "scene/setting_fields.h"
#include "voxel/voxel_method.h"

namespace rad {

namespace {

struct Registry {
  std::mutex mutex;
  std::vector<std::unique_ptr<RadiosityMethod>> methods;
  std::vector<SettingDeclaration> table;

  Registry() {
    methods.push_back(makePathTracerMethod());
    methods.push_back(makePatchMethod());
    methods.push_back(makeVoxelMethod());
    rebuildTable();
  }

  // The general settings first, then each method's, each marked as its own.
  void rebuildTable() {
    std::vector<std::string> names;
    for (const auto& m : methods) names.push_back(m->name());
    table = generalSettingDeclarations(names);
    for (const auto& m : methods)
      for (SettingDeclaration& d : m->settingDeclarations()) {
        d.owner = m.get();
        table.push_back(std::move(d));
      }
  }
};

Registry& registry() {
  static Registry r;
  return r;
}

std::string namesOf(const std::vector<const RadiosityMethod*>& methods) {
  std::vector<std::string> names;
  for (const RadiosityMethod* m : methods) names.push_back(m->name());
  return fmt::format("{}", fmt::join(names, ", "));
}

}  // namespace

std::unique_ptr<MethodModel> RadiosityMethod::prepare(const Scene& /*scene*/,
                                                      const RayCaster& /*caster*/,
                                                      const MethodSettings& /*settings*/) const {
  throw InputError("--method " + name(),
                   fmt::format("renders pictures only; the methods that solve the surfaces: {}",
                               fmt::join(methodsWith(&MethodCapabilities::surfaceSolution), ", ")));
}

RenderedPicture RadiosityMethod::renderPicture(const Scene& /*scene*/, const RayCaster& /*caster*/,
                                               const Camera& /*camera*/,
                                               const MethodSettings& /*settings*/,
                                               const ProgressCallback& /*progress*/) const {
  throw std::logic_error(name() + " solves the surfaces: its pictures are of its solution");
}

EstimatedObjects RadiosityMethod::estimateObjects(const Scene& /*scene*/,
                                                  const RayCaster& /*caster*/,
                                                  int /*pointsPerObject*/,
                                                  const MethodSettings& /*settings*/,
                                                  const ProgressCallback& /*progress*/) const {
  throw std::logic_error(name() + " solves the surfaces: its means are of its solution");
}

EstimatedSensors RadiosityMethod::estimateSensors(const Scene& /*scene*/,
                                                  const RayCaster& /*caster*/,
                                                  std::span<const SensorPoint> /*points*/,
                                                  const SensorSettings& /*sensors*/,
                                                  const MethodSettings& /*settings*/,
                                                  const ProgressCallback& /*progress*/) const {
  throw std::logic_error(name() + " solves the surfaces: its sensors read its solution");
}

std::unique_ptr<SurfaceSolution> MethodModel::load(const std::string& path,
                                                   std::span<const Light> /*lights*/) const {
  throw InputError(path,
                   fmt::format("this method keeps no solution files (those that do: {})",
                               fmt::join(methodsWith(&MethodCapabilities::saveSolution), ", ")));
}

std::unique_ptr<Relighting> MethodModel::startRelighting(
    std::span<const Light> /*lights*/, const std::string& /*solutionFile*/,
    const RelightSettings& /*settings*/, const ProgressCallback& /*progress*/) const {
  throw InputError("--method",
                   fmt::format("this method does not relight (those that do: {})",
                               fmt::join(methodsWith(&MethodCapabilities::relight), ", ")));
}

std::vector<const RadiosityMethod*> radiosityMethods() {
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  std::vector<const RadiosityMethod*> out;
  for (const auto& m : r.methods) out.push_back(m.get());
  return out;
}

const RadiosityMethod* findRadiosityMethod(std::string_view name) {
  for (const RadiosityMethod* m : radiosityMethods())
    if (m->name() == name) return m;
  return nullptr;
}

const RadiosityMethod& radiosityMethod(std::string_view name) {
  if (const RadiosityMethod* m = findRadiosityMethod(name)) return *m;
  throw InputError("--method " + std::string(name),
                   "no such method (available: " + namesOf(radiosityMethods()) + ")");
}

void registerRadiosityMethod(std::unique_ptr<RadiosityMethod> method) {
  if (findRadiosityMethod(method->name()))
    throw std::invalid_argument("a method named '" + method->name() + "' is registered already");
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  r.methods.push_back(std::move(method));
  r.rebuildTable();
}

std::vector<std::string> methodsWith(bool MethodCapabilities::*capability) {
  std::vector<std::string> names;
  for (const RadiosityMethod* m : radiosityMethods())
    if (m->capabilities().*capability) names.push_back(m->name());
  return names;
}

bool SettingDeclaration::readBy(const RadiosityMethod& method) const {
  if (owner) return owner == &method;
  return !readIf || readIf(method.capabilities());
}

const std::vector<SettingDeclaration>& solverSettingDeclarations() {
  return registry().table;
}

const SettingDeclaration* findSolverSetting(std::string_view name) {
  for (const SettingDeclaration& d : solverSettingDeclarations())
    if (d.name == name) return &d;
  return nullptr;
}

MethodSettings resolveMethodSettings(const SolverSettings& scene, const SolverSettings& given,
                                     const std::string& source) {
  MethodSettings m;
  m.cacheDir = defaultPatchCacheDir();
  for (const SolverSettings* layer : {&scene, &given})
    for (const auto& [name, value] : layer->values) {
      const SettingDeclaration* d = findSolverSetting(name);
      const std::string where = layer == &scene ? source + ": /solver/" + name : name;
      if (!d) {
        std::vector<std::string> names;
        for (const SettingDeclaration& known : solverSettingDeclarations())
          names.push_back(known.name);
        throw InputError(where,
                         fmt::format("unknown key (expected one of: {})", fmt::join(names, ", ")));
      }
      const SettingValue typed = d->typed(value);
      if (const std::string why = d->problem(typed); !why.empty()) throw InputError(where, why);
      d->apply(m, typed);
    }
  const bool sppGiven = scene.values.contains("spp") || given.values.contains("spp");
  if (!sppGiven) m.samplesPerPixel = radiosityMethod(m.method).defaultSamplesPerPixel();
  return m;
}

std::vector<std::pair<std::string, SettingValue>> settingsOf(const MethodSettings& settings) {
  const RadiosityMethod& method = radiosityMethod(settings.method);
  std::vector<std::pair<std::string, SettingValue>> out;
  for (const SettingDeclaration& d : solverSettingDeclarations())
    if (d.readBy(method)) out.emplace_back(d.name, d.current(settings));
  return out;
}

}  // namespace rad
