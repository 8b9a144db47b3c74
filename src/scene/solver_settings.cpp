// The one table of the methods' settings (solver_settings.h) and what reads it.
#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/solver_settings.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <type_traits>

namespace rad {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
const std::string kGeneral = "General", kPathTracer = "Path tracer", kVoxel = "Voxel method",
                  kPatch = "Patch method";

template <class T>
T as(const SettingValue& v) {
  if constexpr (std::is_same_v<T, bool>)
    return std::get<bool>(v);
  else if constexpr (std::is_same_v<T, std::string>)
    return std::get<std::string>(v);
  else if constexpr (std::is_integral_v<T>)
    return T(std::get<int64_t>(v));
  else
    return T(std::get<double>(v));
}

template <class T>
SettingValue valueOf(const T& v) {
  if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, std::string>)
    return v;
  else if constexpr (std::is_integral_v<T>)
    return int64_t(v);
  else
    return double(v);
}

template <class T>
SettingType typeOf() {
  if constexpr (std::is_same_v<T, bool>)
    return SettingType::Flag;
  else if constexpr (std::is_same_v<T, std::string>)
    return SettingType::Text;
  else if constexpr (std::is_integral_v<T>)
    return SettingType::Integer;
  else
    return SettingType::Number;
}

// The methods that read a group's settings: one method's group its own, the general ones all.
std::vector<std::string> methodsOf(const std::string& group) {
  if (group == kPathTracer) return {"pathtrace"};
  if (group == kVoxel) return {"voxel"};
  if (group == kPatch) return {"patch"};
  return {};
}

// A setting stored in one field of one method's settings.
template <class Section, class Field>
SettingDeclaration field(std::string name, const std::string& group,
                         Section MethodSettings::*section, Field Section::*member, std::string help,
                         double min = 0.0, double max = 0.0, bool minOpen = false,
                         bool maxOpen = false) {
  SettingDeclaration d;
  d.name = std::move(name);
  d.type = typeOf<Field>();
  d.group = group;
  d.methods = methodsOf(group);
  d.help = std::move(help);
  d.min = min;
  d.max = max;
  d.minOpen = minOpen;
  d.maxOpen = maxOpen;
  d.apply = [section, member](MethodSettings& m, const SettingValue& v) {
    (m.*section).*member = as<Field>(v);
  };
  d.current = [section, member](const MethodSettings& m) { return valueOf((m.*section).*member); };
  return d;
}

// A setting whose names stand for an enum's values (the library's table of names).
template <class Section, class Enum, size_t N>
SettingDeclaration choice(std::string name, const std::string& group,
                          Section MethodSettings::*section, Enum Section::*member,
                          const NamedChoice<Enum> (&names)[N], std::string help) {
  SettingDeclaration d;
  d.name = std::move(name);
  d.type = SettingType::Choice;
  d.group = group;
  d.methods = methodsOf(group);
  d.help = std::move(help);
  d.choices = choiceNames(names);
  d.apply = [section, member, &names](MethodSettings& m, const SettingValue& v) {
    (m.*section).*member = *choiceNamed(names, std::get<std::string>(v));
  };
  d.current = [section, member, &names](const MethodSettings& m) {
    return SettingValue(std::string(choiceName(names, (m.*section).*member)));
  };
  return d;
}

std::vector<SettingDeclaration> declare() {
  using M = MethodSettings;
  std::vector<SettingDeclaration> d;
  {
    SettingDeclaration method;
    method.name = "method";
    method.type = SettingType::Choice;
    method.group = kGeneral;
    method.help = "Light transport method";
    method.choices = {"pathtrace", "patch", "voxel"};
    method.defaultText = "pathtrace for render, patch for solve";
    method.apply = [](M& m, const SettingValue& v) { m.method = std::get<std::string>(v); };
    method.current = [](const M& m) { return SettingValue(m.method); };
    d.push_back(method);
  }
  d.push_back(field("spp", kGeneral, &M::pathTracer, &PathTracerSettings::samplesPerPixel,
                    "Samples per pixel: paths (pathtrace) or camera rays (others, one per cell of "
                    "a square grid)",
                    1, 1 << 20));
  d.back().defaultText = "64 for pathtrace, 16 for the others";
  d.push_back(field("seed", kGeneral, &M::pathTracer, &PathTracerSettings::seed,
                    "Random seed (same seed, same result)", 0, 9.2e18));
  d.back().apply = [](M& m, const SettingValue& v) {  // every method draws from it
    m.pathTracer.seed = m.voxel.seed = m.patch.seed = uint64_t(std::get<int64_t>(v));
  };
  d.push_back(field("light_groups", kGeneral, &M::patch, &PatchRadiositySettings::lightGroups,
                    "Solve each light group apart (patch, voxel: a solve per group), so that "
                    "--group dims, tints or switches them off with their full bounce; on with "
                    "any --group"));
  d.back().methods = {"patch", "voxel"};
  d.back().apply = [](M& m, const SettingValue& v) {
    m.patch.lightGroups = m.voxel.lightGroups = std::get<bool>(v);
  };
  d.push_back(field("max_depth", kPathTracer, &M::pathTracer, &PathTracerSettings::maxDepth,
                    "Path tracer bounce limit (Russian roulette ends paths long before)", 1,
                    100000));
  d.push_back(field("tolerance", kGeneral, &M::voxel, &VoxelRadiositySettings::tolerance,
                    "Stop once the relative residual is below this: the light not yet solved "
                    "over the light put in (patch: the unsolved power; voxel: the power still "
                    "bouncing, 0: every --iterations); a solve that ends above it warns",
                    0, kInfinity));
  d.back().methods = {"patch", "voxel"};
  d.back().apply = [](M& m, const SettingValue& v) {
    m.voxel.tolerance = m.patch.tolerance = std::get<double>(v);
  };
  d.back().current = [](const M& m) {
    return SettingValue(m.method == "patch" ? m.patch.tolerance : m.voxel.tolerance);
  };
  // Voxel method.
  using V = VoxelRadiositySettings;
  d.push_back(field("voxel_size", kVoxel, &M::voxel, &V::voxelSize, "Voxel edge in scene units", 0,
                    kInfinity, true));
  d.back().defaultText = "from --voxels";
  d.push_back(field("voxels", kVoxel, &M::voxel, &V::targetVoxels,
                    "Approximate number of surface voxels", 1, 4294967296.0));
  d.push_back(field("sphere_radius", kVoxel, &M::voxel, &V::sphereRadius,
                    "Radius R of the discrete sphere of directions (38: 14,790 directions)", 1,
                    200));
  d.push_back(field("later_sphere_radius", kVoxel, &M::voxel, &V::laterSphereRadius,
                    "Sphere radius for the sweeps after the first, whose light is smoother", 1,
                    200));
  d.back().defaultText = "--sphere-radius";
  d.push_back(field("iterations", kVoxel, &M::voxel, &V::iterations,
                    "Sweeps over all directions at most, before --tolerance is reached (all of "
                    "them with --tolerance 0)",
                    1, 100000));
  d.push_back(field("tangent_correction", kVoxel, &M::voxel, &V::tangentCorrection,
                    "Look through voxels a line only grazes"));
  d.push_back(field("first_shot", kVoxel, &M::voxel, &V::directFirstShot,
                    "Direct light by shadow rays before the sweeps"));
  d.push_back(field("direct_samples", kVoxel, &M::voxel, &V::directSamples,
                    "Shadow-ray samples of the emitting surfaces per voxel side for the first shot",
                    1, 1 << 20));
  d.push_back(field("normalize", kVoxel, &M::voxel, &V::normalize,
                    "Per-voxel normalization of the direction factors"));
  d.push_back(field("jitter_lines", kVoxel, &M::voxel, &V::jitterLines,
                    "Shift each direction's lines every iteration"));
  d.push_back(field("tail_estimate", kVoxel, &M::voxel, &V::estimateTail,
                    "Add the bounces after the last iteration, extrapolated"));
  // Patch method.
  using P = PatchRadiositySettings;
  d.push_back(field("patch_size", kPatch, &M::patch, &P::patchSize,
                    "Longest patch edge in scene units (the base level)", 0, kInfinity, true));
  d.back().defaultText = "from --patches";
  d.push_back(
      field("patches", kPatch, &M::patch, &P::targetPatches,
            "Approximate number of patches (the base level) beyond the one each face is at least",
            1, 4294967296.0));
  d.push_back(choice("ff_estimator", kPatch, &M::patch, &P::estimator, kFormFactorEstimatorNames,
                     "Form factors by: hemisphere (rays from each patch), pairwise (point pairs), "
                     "exact (point-to-polygon, visibility rays)"));
  d.push_back(field("ff_rays", kPatch, &M::patch, &P::formFactorRays,
                    "Rays per patch (hemisphere), point pairs per patch pair (pairwise) or points "
                    "per patch (exact)",
                    1, 1 << 24));
  d.push_back(field("ff_threshold", kPatch, &M::patch, &P::formFactorThreshold,
                    "Drop form factors below this, passing their light to the patch's largest", 0,
                    1, false, true));
  d.push_back(
      field("cache_dir", kGeneral, &M::patch, &P::cacheDir,
            "Cache directory: form-factor tables (patch), checkpoints to go on from after a "
            "kill or Ctrl-C (voxel, pathtrace); none: no cache"));
  d.back().defaultText = "$XDG_CACHE_HOME/radiosity, else ~/.cache/radiosity";
  d.back().apply = [](M& m, const SettingValue& v) {
    const std::string& dir = std::get<std::string>(v);
    m.patch.cacheDir = dir == "none" ? "" : dir;
    m.voxel.checkpointDir = m.patch.cacheDir;
    m.pathTracer.checkpointDir = m.patch.cacheDir;
  };
  {
    SettingDeclaration cap;
    cap.name = "cache_max_mb";
    cap.type = SettingType::Integer;
    cap.group = kGeneral;
    cap.help = "The cache directory's cap: its least recently used files go first (MB)";
    cap.min = 1;
    cap.max = 1e9;
    cap.apply = [](M& m, const SettingValue& v) { m.cacheMaxMegabytes = std::get<int64_t>(v); };
    cap.current = [](const M& m) { return SettingValue(m.cacheMaxMegabytes); };
    d.push_back(cap);
  }
  d.push_back(choice("solver", kPatch, &M::patch, &P::solver, kPatchSolverNames, "Linear solver"));
  d.push_back(field("max_iterations", kPatch, &M::patch, &P::maxIterations,
                    "Solver sweeps at most (progressive: shots / patches)", 1, 1e8));
  d.push_back(choice("shading", kPatch, &M::patch, &P::shading, kPatchShadingNames,
                     "Rendering of the patches"));
  d.push_back(field("light_samples", kPatch, &M::patch, &P::lightSamples,
                    "Points per patch (rounded up to a square) at which point, spot and IES light "
                    "is averaged",
                    1, 1 << 16));
  d.push_back(field("refine_levels", kPatch, &M::patch, &P::refineLevels,
                    "Adaptive subdivision for point, spot and IES lights: levels below the base "
                    "patch size at most (0: none)",
                    0, 8));
  d.push_back(field("refine_threshold", kPatch, &M::patch, &P::refineThreshold,
                    "Split neighbouring patches whose direct light differs by more than this, "
                    "relative",
                    0, kInfinity, true));
  return d;
}

std::string number(double v) {
  if (std::isinf(v)) return "inf";
  if (v == std::floor(v) && std::abs(v) < 1e15) return fmt::format("{:.0f}", v);
  return fmt::format("{:g}", v);
}

std::string rangeText(const SettingDeclaration& d) {
  return fmt::format("{}{}, {}{}", d.minOpen ? "(" : "[", number(d.min), number(d.max),
                     d.maxOpen || std::isinf(d.max) ? ")" : "]");
}

std::string show(const SettingValue& v) {
  return std::visit(
      [](const auto& x) -> std::string {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, bool>)
          return x ? "true" : "false";
        else if constexpr (std::is_same_v<T, std::string>)
          return "'" + x + "'";
        else
          return number(double(x));
      },
      v);
}

}  // namespace

std::string SettingDeclaration::flag() const {
  std::string f = "--" + name;
  std::replace(f.begin(), f.end(), '_', '-');
  return f;
}

bool SettingDeclaration::readBy(std::string_view method) const {
  return methods.empty() || std::find(methods.begin(), methods.end(), method) != methods.end();
}

std::string SettingDeclaration::problem(const SettingValue& value) const {
  switch (type) {
    case SettingType::Flag:
      return std::holds_alternative<bool>(value) ? "" : "expected true or false";
    case SettingType::Text:
      return std::holds_alternative<std::string>(value) ? "" : "expected a string";
    case SettingType::Choice: {
      const std::string* s = std::get_if<std::string>(&value);
      if (s && std::find(choices.begin(), choices.end(), *s) != choices.end()) return "";
      return fmt::format("{} is not one of {}", s ? "'" + *s + "'" : show(value),
                         fmt::join(choices, ", "));
    }
    case SettingType::Integer:
    case SettingType::Number: {
      double v;
      if (const int64_t* i = std::get_if<int64_t>(&value))
        v = double(*i);
      else if (const double* x = std::get_if<double>(&value); x && type == SettingType::Number)
        v = *x;
      else
        return fmt::format("expected {} in {}",
                           type == SettingType::Integer ? "an integer" : "a number",
                           rangeText(*this));
      const bool below = minOpen ? !(v > min) : !(v >= min);
      const bool above = maxOpen ? !(v < max) : !(v <= max);
      if (below || above || std::isnan(v))
        return fmt::format("{} out of range {}", show(value), rangeText(*this));
      return "";
    }
  }
  return "";
}

std::optional<SettingValue> SettingDeclaration::parse(const std::string& text,
                                                      std::string& why) const {
  SettingValue v;
  switch (type) {
    case SettingType::Flag:
      if (text != "true" && text != "false") {
        why = "expected true or false";
        return std::nullopt;
      }
      v = text == "true";
      break;
    case SettingType::Text:
    case SettingType::Choice:
      v = text;
      break;
    case SettingType::Integer: {
      int64_t i = 0;
      const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), i);
      if (ec != std::errc() || end != text.data() + text.size()) {
        why = fmt::format("'{}' is not an integer in {}", text, rangeText(*this));
        return std::nullopt;
      }
      v = i;
      break;
    }
    case SettingType::Number: {
      double x = 0.0;
      const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), x);
      if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(x)) {
        why = fmt::format("'{}' is not a number in {}", text, rangeText(*this));
        return std::nullopt;
      }
      v = x;
      break;
    }
  }
  why = problem(v);
  if (!why.empty()) return std::nullopt;
  return v;
}

std::string SettingDeclaration::fullHelp() const {
  std::string text = help;
  if (type == SettingType::Choice && help.find(choices.front()) == std::string::npos)
    text += fmt::format(": {}", fmt::join(choices, ", "));
  if (type == SettingType::Integer || type == SettingType::Number)
    text += fmt::format(", in {}", rangeText(*this));
  std::string fallback = defaultText;
  if (fallback.empty()) {
    const SettingValue v = current(MethodSettings{});
    fallback = std::holds_alternative<std::string>(v) ? std::get<std::string>(v) : show(v);
  }
  if (!(type == SettingType::Text && defaultText.empty()))
    text += fmt::format(" (default {})", fallback);
  return text;
}

const std::vector<SettingDeclaration>& solverSettingDeclarations() {
  static const std::vector<SettingDeclaration> declarations = declare();
  return declarations;
}

const SettingDeclaration* findSolverSetting(std::string_view name) {
  for (const SettingDeclaration& d : solverSettingDeclarations())
    if (d.name == name) return &d;
  return nullptr;
}

MethodSettings resolveMethodSettings(const SolverSettings& scene, const SolverSettings& given,
                                     const std::string& source) {
  MethodSettings m;
  m.patch.cacheDir = defaultPatchCacheDir();
  m.voxel.checkpointDir = m.patch.cacheDir;
  m.pathTracer.checkpointDir = m.patch.cacheDir;
  for (const SolverSettings* layer : {&scene, &given})
    for (const auto& [name, value] : layer->values) {
      const SettingDeclaration* d = findSolverSetting(name);
      const std::string where = layer == &scene ? source + ": /solver/" + name : name;
      if (!d) throw InputError(where, "unknown setting");
      if (const std::string why = d->problem(value); !why.empty()) throw InputError(where, why);
      d->apply(m, value);
    }
  const bool sppGiven = scene.values.contains("spp") || given.values.contains("spp");
  if (m.method != "pathtrace" && !sppGiven) m.pathTracer.samplesPerPixel = 16;
  return m;
}

std::vector<std::pair<std::string, SettingValue>> settingsOf(const MethodSettings& settings) {
  std::vector<std::pair<std::string, SettingValue>> out;
  for (const SettingDeclaration& d : solverSettingDeclarations())
    if (d.readBy(settings.method)) out.emplace_back(d.name, d.current(settings));
  return out;
}

}  // namespace rad
