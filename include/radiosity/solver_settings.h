#pragma once
// Every setting of the light-transport methods, declared once: its name (the scene's "solver"
// key; the flag is "--" + the name with '-' for '_'), its type and valid range, its help, and
// where its value goes. The general settings are declared here; each method declares its own
// beside it (RadiosityMethod::settingDeclarations, radiosity_method.h), and the table is the
// general ones and every registered method's. The command line, the scene file, validation and
// the stats all read these declarations, so a setting cannot mean one thing as a flag and another
// as a key.

#include <radiosity/process_share.h>
#include <radiosity/scene.h>

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <typeindex>
#include <vector>

namespace rad {

class RadiosityMethod;

/// What a method offers. A command or request that needs a capability the method lacks is
/// refused, naming the methods that have it (methodsWith).
struct MethodCapabilities {
  /// Solves the surfaces into a SurfaceSolution (solve, exports, the viewer, pictures of the
  /// solution); without it, the method renders pictures by itself (renderPicture).
  bool surfaceSolution = true;
  bool relight = false;       ///< keeps a solution up to date as lights move (startRelighting)
  bool saveSolution = false;  ///< solution files (SurfaceSolution::save, MethodModel::load)
  bool lightGroups = false;   ///< solves light groups apart (the light_groups setting)
  bool processes = false;     ///< splits its work among processes (MPI ranks)
};

/// A choice as scene files, the command line and the stats spell it. One table per enum, so that
/// a new value is one more row wherever names are read or written.
template <class Enum>
struct NamedChoice {
  const char* name;
  Enum value;
};
/// The names of a table's choices, in its order.
template <class Enum, size_t N>
std::vector<std::string> choiceNames(const NamedChoice<Enum> (&choices)[N]) {
  std::vector<std::string> names;
  for (const NamedChoice<Enum>& c : choices) names.push_back(c.name);
  return names;
}
/// The choice a name stands for, if any.
template <class Enum, size_t N>
std::optional<Enum> choiceNamed(const NamedChoice<Enum> (&choices)[N], std::string_view name) {
  for (const NamedChoice<Enum>& c : choices)
    if (name == c.name) return c.value;
  return std::nullopt;
}
/// The name of a choice ("" for a value the table lacks).
template <class Enum, size_t N>
const char* choiceName(const NamedChoice<Enum> (&choices)[N], Enum value) {
  for (const NamedChoice<Enum>& c : choices)
    if (c.value == value) return c.name;
  return "";
}

/// The settings of a run: which method, the general settings every method reads as far as it
/// can, and each method's own section (its settings struct, e.g. PatchRadiositySettings, as its
/// declarations fill it).
class MethodSettings {
 public:
  std::string method = "pathtrace";  ///< a registered method's name (radiosity_method.h)
  int samplesPerPixel = 64;          ///< paths (pathtrace) or camera rays a pixel (the others)
  uint64_t seed = 1;
  bool lightGroups = false;  ///< solve each light group apart (methods that can)
  double tolerance = 1e-3;   ///< relative residual at which an iterative solve stops
  /// Form-factor tables and checkpoints; empty: no cache.
  std::string cacheDir;
  /// The cache directory's cap, in MB.
  int64_t cacheMaxMegabytes = 4096;
  /// Set by the run, not a setting: the processes the work is split among (one by default), and
  /// whether the solution keeps its direct light apart from the bounces (pictures with per-pixel
  /// direct light, saved solutions).
  ProcessShare processes;
  bool keepDirectLight = false;
  /// Set by the run: pictures show the irradiance at each hit (false colour), not the radiance.
  bool irradiancePictures = false;

  MethodSettings() = default;
  MethodSettings(const MethodSettings& other);
  MethodSettings& operator=(const MethodSettings& other);
  MethodSettings(MethodSettings&&) noexcept = default;
  MethodSettings& operator=(MethodSettings&&) noexcept = default;

  /// A method's section: its settings struct, default-constructed until a setting is applied.
  template <class Section>
  Section& section() {
    std::unique_ptr<SectionBase>& slot = sections_[std::type_index(typeid(Section))];
    if (!slot) slot = std::make_unique<Held<Section>>();
    return static_cast<Held<Section>&>(*slot).value;
  }
  template <class Section>
  const Section& section() const {
    static const Section defaults{};
    const auto it = sections_.find(std::type_index(typeid(Section)));
    return it == sections_.end() ? defaults : static_cast<const Held<Section>&>(*it->second).value;
  }

 private:
  struct SectionBase {
    virtual ~SectionBase() = default;
    virtual std::unique_ptr<SectionBase> clone() const = 0;
  };
  template <class Section>
  struct Held final : SectionBase {
    Section value{};
    std::unique_ptr<SectionBase> clone() const override { return std::make_unique<Held>(*this); }
  };
  std::map<std::type_index, std::unique_ptr<SectionBase>> sections_;
};

enum class SettingType { Flag, Integer, Number, Choice, Text };

struct SettingDeclaration {
  std::string name;  ///< scene key, e.g. "patch_size"
  SettingType type = SettingType::Number;
  std::string group;            ///< "General", or the method's settingsGroup(), e.g. "Patch method"
  std::string help;             ///< what it does; --help adds the choices, range and default
  double min = 0.0, max = 0.0;  ///< numbers: the valid range
  bool minOpen = false, maxOpen = false;  ///< the ends themselves are not valid
  std::vector<std::string> choices;       ///< Choice: the valid names
  /// The method that declares it (set by the registry); null: a general setting, read by the
  /// methods `readIf` accepts (null: every one).
  const RadiosityMethod* owner = nullptr;
  std::function<bool(const MethodCapabilities&)> readIf;
  /// The default as --help states it, where the method's own default does not say it all.
  std::string defaultText;
  std::function<void(MethodSettings&, const SettingValue&)> apply;
  std::function<SettingValue(const MethodSettings&)> current;

  /// "--patch-size"; a Flag also has "--no-" + the rest.
  std::string flag() const;
  /// Whether `method` reads it.
  bool readBy(const RadiosityMethod& method) const;
  /// `value` as its type holds it: an integral number as an Integer, an integer as a Number
  /// (a scene file's JSON does not say which); anything else unchanged, for problem() to judge.
  SettingValue typed(const SettingValue& value) const;
  /// Why `value` is not valid here (its type, range or choices), or "" if it is.
  std::string problem(const SettingValue& value) const;
  /// The value a command-line word stands for, or nullopt with `why` set.
  std::optional<SettingValue> parse(const std::string& text, std::string& why) const;
  /// The help line: help, choices or range, default.
  std::string fullHelp() const;
};

/// Every setting, in the order --help lists them: the general ones, then each registered
/// method's. Valid until a method is registered.
const std::vector<SettingDeclaration>& solverSettingDeclarations();
/// The declaration of `name`, or nullptr.
const SettingDeclaration* findSolverSetting(std::string_view name);

/// Settings from three layers: the methods' defaults, then the scene's "solver" values, then
/// `given` (the command line's): each later one wins. Where neither sets them: pictures take the
/// method's defaultSamplesPerPixel(), and the cache goes to defaultPatchCacheDir(); a cache_dir
/// of "none" means no cache. Throws InputError for an unknown key, an unknown method or a value
/// its declaration refuses, naming `source` and the key.
MethodSettings resolveMethodSettings(const SolverSettings& scene, const SolverSettings& given,
                                     const std::string& source);

/// The effective value of every setting that the settings' method reads, by name: what the
/// stats file reports and a solution file records.
std::vector<std::pair<std::string, SettingValue>> settingsOf(const MethodSettings& settings);

}  // namespace rad
