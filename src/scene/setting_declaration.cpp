// The declarations of settings (solver_settings.h): how a value is checked, parsed and shown,
// and the general settings every method reads as far as it can.
#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/solver_settings.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <type_traits>

#include "scene/setting_fields.h"

namespace rad {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
const std::string kGeneral = "General";

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

// A general setting stored in a member of MethodSettings itself.
template <class Field>
SettingDeclaration generalField(std::string name, Field MethodSettings::*member, std::string help,
                                SettingRange range = {}) {
  SettingDeclaration d;
  d.name = std::move(name);
  d.type = settingTypeOf<Field>();
  d.group = kGeneral;
  d.help = std::move(help);
  d.min = range.min;
  d.max = range.max;
  d.minOpen = range.minOpen;
  d.maxOpen = range.maxOpen;
  d.apply = [member](MethodSettings& m, const SettingValue& v) { m.*member = settingAs<Field>(v); };
  d.current = [member](const MethodSettings& m) { return settingValueOf(m.*member); };
  return d;
}

}  // namespace

MethodSettings::MethodSettings(const MethodSettings& other)
    : method(other.method),
      samplesPerPixel(other.samplesPerPixel),
      seed(other.seed),
      lightGroups(other.lightGroups),
      tolerance(other.tolerance),
      cacheDir(other.cacheDir),
      cacheMaxMegabytes(other.cacheMaxMegabytes),
      processes(other.processes),
      keepDirectLight(other.keepDirectLight),
      irradiancePictures(other.irradiancePictures) {
  for (const auto& [type, section] : other.sections_) sections_[type] = section->clone();
}

MethodSettings& MethodSettings::operator=(const MethodSettings& other) {
  if (this != &other) *this = MethodSettings(other);
  return *this;
}

std::vector<SettingDeclaration> generalSettingDeclarations(std::vector<std::string> methodNames) {
  using M = MethodSettings;
  std::vector<SettingDeclaration> d;
  d.push_back(generalField("method", &M::method, "Light transport method"));
  d.back().type = SettingType::Choice;
  d.back().choices = std::move(methodNames);
  d.back().defaultText = "each command's own";
  d.push_back(generalField("spp", &M::samplesPerPixel,
                           "Samples per pixel: paths (pathtrace) or camera rays (others, one per "
                           "cell of a square grid)",
                           {1, 1 << 20}));
  d.back().defaultText = "64 for pathtrace, 16 for the others";
  d.push_back(generalField("seed", &M::seed, "Random seed (same seed, same result)", {0, 9.2e18}));
  d.push_back(generalField("light_groups", &M::lightGroups,
                           "Solve each light group apart (patch, voxel: a solve per group), so "
                           "that --group dims, tints or switches them off with their full bounce; "
                           "on with any --group"));
  d.back().readIf = [](const MethodCapabilities& c) { return c.lightGroups; };
  d.push_back(generalField("tolerance", &M::tolerance,
                           "Stop once the relative residual is below this: the light not yet "
                           "solved over the light put in (patch: the unsolved power; voxel: the "
                           "power still bouncing, 0: every --iterations); a solve that ends above "
                           "it warns",
                           {0, kInfinity}));
  d.back().readIf = [](const MethodCapabilities& c) { return c.surfaceSolution; };
  d.push_back(generalField("cache_dir", &M::cacheDir,
                           "Cache directory: form-factor tables (patch), checkpoints to go on "
                           "from after a kill or Ctrl-C (voxel, pathtrace); none: no cache"));
  d.back().defaultText = "$XDG_CACHE_HOME/radiosity, else ~/.cache/radiosity";
  d.back().apply = [](M& m, const SettingValue& v) {
    const std::string& dir = std::get<std::string>(v);
    m.cacheDir = dir == "none" ? "" : dir;
  };
  d.push_back(generalField("cache_max_mb", &M::cacheMaxMegabytes,
                           "The cache directory's cap: its least recently used files go first (MB)",
                           {1, 1e9}));
  return d;
}

std::string SettingDeclaration::flag() const {
  std::string f = "--" + name;
  std::replace(f.begin(), f.end(), '_', '-');
  return f;
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

SettingValue SettingDeclaration::typed(const SettingValue& value) const {
  if (type == SettingType::Integer)
    if (const double* x = std::get_if<double>(&value);
        x && *x == std::floor(*x) && std::abs(*x) < 9.2e18)
      return int64_t(*x);
  if (type == SettingType::Number)
    if (const int64_t* i = std::get_if<int64_t>(&value)) return double(*i);
  return value;
}

}  // namespace rad
