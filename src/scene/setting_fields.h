#pragma once
// Declarations of settings stored in one field of a section of MethodSettings (a method's
// settings struct): the general settings' table and each method's own use them, so that a field
// is named, typed, checked and reported in one line.

#include <radiosity/solver_settings.h>

#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace rad {

template <class T>
T settingAs(const SettingValue& v) {
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
SettingValue settingValueOf(const T& v) {
  if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, std::string>)
    return v;
  else if constexpr (std::is_integral_v<T>)
    return int64_t(v);
  else
    return double(v);
}

template <class T>
SettingType settingTypeOf() {
  if constexpr (std::is_same_v<T, bool>)
    return SettingType::Flag;
  else if constexpr (std::is_same_v<T, std::string>)
    return SettingType::Text;
  else if constexpr (std::is_integral_v<T>)
    return SettingType::Integer;
  else
    return SettingType::Number;
}

/// The range a number setting accepts: [min, max], an end left out where it is open.
struct SettingRange {
  double min = 0.0, max = 0.0;
  bool minOpen = false, maxOpen = false;
};

/// A setting stored in `member` of the settings' section `Section`.
template <class Section, class Field>
SettingDeclaration sectionField(std::string name, std::string group, Field Section::*member,
                                std::string help, SettingRange range = {}) {
  SettingDeclaration d;
  d.name = std::move(name);
  d.type = settingTypeOf<Field>();
  d.group = std::move(group);
  d.help = std::move(help);
  d.min = range.min;
  d.max = range.max;
  d.minOpen = range.minOpen;
  d.maxOpen = range.maxOpen;
  d.apply = [member](MethodSettings& m, const SettingValue& v) {
    m.section<Section>().*member = settingAs<Field>(v);
  };
  d.current = [member](const MethodSettings& m) {
    return settingValueOf(m.section<Section>().*member);
  };
  return d;
}

/// A setting whose names stand for the values of an enum stored in `member` of `Section`.
template <class Section, class Enum, size_t N>
SettingDeclaration sectionChoice(std::string name, std::string group, Enum Section::*member,
                                 const NamedChoice<Enum> (&names)[N], std::string help) {
  SettingDeclaration d;
  d.name = std::move(name);
  d.type = SettingType::Choice;
  d.group = std::move(group);
  d.help = std::move(help);
  d.choices = choiceNames(names);
  d.apply = [member, &names](MethodSettings& m, const SettingValue& v) {
    m.section<Section>().*member = *choiceNamed(names, std::get<std::string>(v));
  };
  d.current = [member, &names](const MethodSettings& m) {
    return SettingValue(std::string(choiceName(names, m.section<Section>().*member)));
  };
  return d;
}

/// The general settings (solver_settings.h): method, spp, seed, light_groups, tolerance,
/// cache_dir, cache_max_mb. `methodNames`: the registered methods, the choices of "method".
std::vector<SettingDeclaration> generalSettingDeclarations(std::vector<std::string> methodNames);

}  // namespace rad
