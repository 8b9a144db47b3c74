#pragma once
// Every setting of the light-transport methods, declared once: its name (the scene's "solver"
// key; the flag is "--" + the name with '-' for '_'), its type and valid range, its help, and
// where its value goes. The command line, the scene file, validation and the stats all read
// these declarations, so a setting cannot mean one thing as a flag and another as a key.

#include <radiosity/patch_radiosity.h>
#include <radiosity/path_tracer.h>
#include <radiosity/scene.h>
#include <radiosity/voxel_radiosity.h>

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rad {

/// The settings of every method, and which method runs.
struct MethodSettings {
  std::string method = "pathtrace";  ///< "pathtrace", "patch" or "voxel"
  /// The cache directory's cap (patch.cacheDir: form-factor tables and checkpoints), in MB.
  int64_t cacheMaxMegabytes = 4096;
  PathTracerSettings pathTracer;
  VoxelRadiositySettings voxel;
  PatchRadiositySettings patch;
};

enum class SettingType { Flag, Integer, Number, Choice, Text };

struct SettingDeclaration {
  std::string name;  ///< scene key, e.g. "patch_size"
  SettingType type = SettingType::Number;
  std::string group;            ///< "General", "Path tracer", "Voxel method" or "Patch method"
  std::string help;             ///< what it does; --help adds the choices, range and default
  double min = 0.0, max = 0.0;  ///< numbers: the valid range
  bool minOpen = false, maxOpen = false;  ///< the ends themselves are not valid
  std::vector<std::string> choices;       ///< Choice: the valid names
  /// The methods that read it ("pathtrace", "patch", "voxel"); empty: every one.
  std::vector<std::string> methods;
  /// The default as --help states it, where the method's own default does not say it all.
  std::string defaultText;
  std::function<void(MethodSettings&, const SettingValue&)> apply;
  std::function<SettingValue(const MethodSettings&)> current;

  /// "--patch-size"; a Flag also has "--no-" + the rest.
  std::string flag() const;
  /// Whether `method` reads it.
  bool readBy(std::string_view method) const;
  /// Why `value` is not valid here (its type, range or choices), or "" if it is.
  std::string problem(const SettingValue& value) const;
  /// The value a command-line word stands for, or nullopt with `why` set.
  std::optional<SettingValue> parse(const std::string& text, std::string& why) const;
  /// The help line: help, choices or range, default.
  std::string fullHelp() const;
};

/// Every setting, in the order --help lists them.
const std::vector<SettingDeclaration>& solverSettingDeclarations();
/// The declaration of `name`, or nullptr.
const SettingDeclaration* findSolverSetting(std::string_view name);

/// Settings from three layers: the methods' defaults, then the scene's "solver" values, then
/// `given` (the command line's): each later one wins. Where neither sets them: radiosity
/// pictures take 16 camera rays a pixel (the path tracer 64 paths), and the patch cache goes to
/// defaultPatchCacheDir(); a cache_dir of "none" means no cache. Throws InputError for a value
/// its declaration refuses, naming `source` and the key.
MethodSettings resolveMethodSettings(const SolverSettings& scene, const SolverSettings& given,
                                     const std::string& source);

/// The effective value of every setting that `method` reads (and the general ones), by name:
/// what the stats file reports.
std::vector<std::pair<std::string, SettingValue>> settingsOf(const MethodSettings& settings);

}  // namespace rad
