#pragma once
// The scene file's JSON reader: every value checked against its type and range, every object's
// keys against those it may have, and a message that names the file and the JSON path of what is
// wrong. Shared by the readers of the scene file's parts.

#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/scene_builder.h>
#include <radiosity/types.h>

#include <algorithm>
#include <cmath>
#include <glm/gtx/component_wise.hpp>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>

namespace rad {

using Json = nlohmann::json;

/// A value from the file for a message: compact JSON, cut short when long.
inline std::string brief(const Json& j) {
  constexpr size_t kMaxShown = 60;
  const std::string text = j.dump(-1, ' ', true, Json::error_handler_t::replace);
  if (text.size() <= kMaxShown) return text;
  return fmt::format("{}... ({} bytes)", text.substr(0, kMaxShown), text.size());
}

/// Reads values of one file, naming it and the JSON path in every InputError.
class JsonReader {
 public:
  explicit JsonReader(std::string path) : path_(std::move(path)) {}

  [[noreturn]] void fail(const std::string& ptr, const std::string& what) const {
    // A pointer holds the file's keys, which may be of any length.
    constexpr size_t kMaxPointer = 160;
    const std::string shown = ptr.size() <= kMaxPointer ? ptr : ptr.substr(0, kMaxPointer) + "...";
    throw InputError(path_ + ": " + (ptr.empty() ? "/" : shown), what);
  }

  void requireObject(const Json& j, const std::string& ptr) const {
    if (!j.is_object()) fail(ptr, fmt::format("expected an object, got {}", j.type_name()));
  }

  void checkKeys(const Json& j, const std::string& ptr,
                 std::initializer_list<const char*> allowed) const {
    requireObject(j, ptr);
    for (const auto& item : j.items()) {
      const std::string& key = item.key();
      if (std::none_of(allowed.begin(), allowed.end(), [&](const char* a) { return key == a; }))
        fail(ptr + "/" + key,
             fmt::format("unknown key (expected one of: {})", fmt::join(allowed, ", ")));
    }
  }

  double number(const Json& j, const std::string& ptr) const {
    if (!j.is_number()) fail(ptr, fmt::format("expected a number, got {}", j.type_name()));
    const double v = j.get<double>();
    if (!std::isfinite(v)) fail(ptr, "expected a finite number");
    return v;
  }

  int64_t integer(const Json& j, const std::string& ptr, int64_t lo, int64_t hi) const {
    if (!j.is_number_integer() &&
        !(j.is_number() && j.get<double>() == std::floor(j.get<double>())))
      fail(ptr, fmt::format("expected an integer in [{}, {}], got {}", lo, hi, brief(j)));
    const double v = j.get<double>();
    if (v < double(lo) || v > double(hi))
      fail(ptr, fmt::format("{} out of range [{}, {}]", brief(j), lo, hi));
    return j.is_number_unsigned() ? int64_t(j.get<uint64_t>()) : j.get<int64_t>();
  }

  std::string string(const Json& j, const std::string& ptr) const {
    if (!j.is_string()) fail(ptr, fmt::format("expected a string, got {}", j.type_name()));
    return j.get<std::string>();
  }

  bool boolean(const Json& j, const std::string& ptr) const {
    if (!j.is_boolean()) fail(ptr, fmt::format("expected true or false, got {}", j.type_name()));
    return j.get<bool>();
  }

  Vec3 vec3(const Json& j, const std::string& ptr) const {
    if (!j.is_array() || j.size() != 3)
      fail(ptr, fmt::format("expected an array of 3 numbers, got {}", brief(j)));
    Vec3 v;
    for (int i = 0; i < 3; ++i) {
      const std::string at = fmt::format("{}/{}", ptr, i);
      v[i] = float(number(j[size_t(i)], at));
      if (!std::isfinite(v[i])) fail(at, "expected a number within the 32-bit float range");
    }
    return v;
  }

  /// A position in the scene: within kMaxSceneCoordinate, like the geometry's vertices.
  Vec3 point(const Json& j, const std::string& ptr) const {
    const Vec3 p = vec3(j, ptr);
    if (glm::compMax(glm::abs(p)) > kMaxSceneCoordinate)
      fail(ptr, fmt::format("({}, {}, {}) is beyond {:g} scene units", p.x, p.y, p.z,
                            kMaxSceneCoordinate));
    return p;
  }

  /// A colour whose components must lie in [lo, hi) (or [lo, inf) when hi is infinite).
  Color color(const Json& j, const std::string& ptr, const char* name, double lo, double hi) const {
    const Vec3 c = vec3(j, ptr);
    // Light (intensity, emission) is bounded only by kMaxLight; other colours by a range of
    // their own.
    const bool light = hi >= kMaxLight;
    for (int i = 0; i < 3; ++i)
      if (!(c[i] >= lo && c[i] < hi))
        fail(ptr, !light       ? fmt::format("{} {} must be in [{}, {})", name, c[i], lo, hi)
                  : c[i] >= lo ? fmt::format("{} {:g} must be below {:g}", name, c[i], hi)
                               : fmt::format("{} {} must be >= {}", name, c[i], lo));
    return c;
  }

  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace rad
