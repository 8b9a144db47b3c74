// Reads the JSON scene file of docs/ARCHITECTURE.md. Every key is checked against the keys its
// object may have (a typo must not pass silently, as in pbrt's ReportUnused), and every value
// against its type and range, so a message names the JSON path of the bad value.

#include "scene/io/scene_json.h"

#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/ies_profile.h>
#include <radiosity/message_text.h>
#include <radiosity/scene_builder.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtx/component_wise.hpp>
#include <glm/gtx/transform.hpp>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <set>

#include "core/json_nesting.h"
#include "scene/io/exr_reader.h"
#include "scene/io/gltf_loader.h"
#include "scene/io/json_reader.h"
#include "scene/io/obj_loader.h"
#include "scene/io/sensor_json.h"
#include "scene/io/text_file.h"
#include "scene/sun_position.h"

namespace rad {

namespace {

// The scene's zenith where it names none.
constexpr Vec3 kDefaultUp(0.0f, 1.0f, 0.0f);

std::string lowerExtension(const std::string& file) {
  const size_t dot = file.find_last_of('.');
  const size_t slash = file.find_last_of("/\\");
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = file.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

glm::mat4 readTransform(const JsonReader& r, const Json& j, const std::string& ptr) {
  r.checkKeys(j, ptr, {"translate", "rotate_deg", "scale"});
  glm::mat4 m(1.0f);
  if (j.contains("translate")) m = glm::translate(r.vec3(j["translate"], ptr + "/translate"));
  if (j.contains("rotate_deg")) {
    const Vec3 a = glm::radians(r.vec3(j["rotate_deg"], ptr + "/rotate_deg"));
    m = m * glm::rotate(a.z, Vec3(0, 0, 1)) * glm::rotate(a.y, Vec3(0, 1, 0)) *
        glm::rotate(a.x, Vec3(1, 0, 0));
  }
  if (j.contains("scale")) {
    const Json& s = j["scale"];
    const Vec3 scale =
        s.is_number() ? Vec3(float(r.number(s, ptr + "/scale"))) : r.vec3(s, ptr + "/scale");
    if (scale.x == 0.0f || scale.y == 0.0f || scale.z == 0.0f)
      r.fail(ptr + "/scale", "scale components must be non-zero");
    m = m * glm::scale(scale);
  }
  return m;
}

// A mesh file ("file", optional "transform") of the entry at `ptr` into `builder`.
void readMeshFile(const JsonReader& r, const Json& g, const std::string& ptr,
                  SceneBuilder& builder) {
  if (!g.contains("file")) r.fail(ptr, "missing key \"file\"");
  const std::string file =
      resolvePath(parentDirectory(r.path()), r.string(g["file"], ptr + "/file"));
  const glm::mat4 m = g.contains("transform") ? readTransform(r, g["transform"], ptr + "/transform")
                                              : glm::mat4(1.0f);
  const std::string ext = lowerExtension(file);
  if (ext == ".obj")
    loadObj(builder, file, m);
  else if (ext == ".gltf" || ext == ".glb")
    loadGltf(builder, file, m);
  else
    r.fail(ptr + "/file", fmt::format("unsupported geometry extension {} (expected .obj, "
                                      ".gltf or .glb)",
                                      quotedToken(ext)));
}

// A geometry entry's "material": every face its file gave takes the material of that name.
struct MaterialAssignment {
  size_t firstFace = 0, endFace = 0;
  std::string material, ptr;
};

std::vector<MaterialAssignment> readGeometry(const JsonReader& r, const Json& list,
                                             SceneBuilder& builder) {
  if (!list.is_array())
    r.fail("/geometry", fmt::format("expected an array, got {}", list.type_name()));
  std::vector<MaterialAssignment> assignments;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string ptr = fmt::format("/geometry/{}", i);
    r.checkKeys(list[i], ptr, {"file", "transform", "material"});
    const size_t firstFace = builder.scene().faces.size();
    readMeshFile(r, list[i], ptr, builder);
    if (list[i].contains("material"))
      assignments.push_back({firstFace, builder.scene().faces.size(),
                             r.string(list[i]["material"], ptr + "/material"), ptr + "/material"});
  }
  return assignments;
}

// Gives the faces of each assignment its material (one of the files', or one "materials" made).
void assignMaterials(const JsonReader& r, const std::vector<MaterialAssignment>& assignments,
                     Scene& scene) {
  for (const MaterialAssignment& a : assignments) {
    const auto it = std::find_if(scene.materials.begin(), scene.materials.end(),
                                 [&](const Material& m) { return m.name == a.material; });
    if (it == scene.materials.end())
      r.fail(a.ptr, fmt::format("no material named {} (define it under \"materials\")",
                                quotedToken(a.material)));
    for (size_t f = a.firstFace; f < a.endFace; ++f)
      scene.faces[f].material = uint32_t(it - scene.materials.begin());
  }
}

std::vector<ObjectKeyframe> readObjectPath(const JsonReader& r, const Json& j,
                                           const std::string& ptr) {
  if (!j.is_array() || j.empty()) r.fail(ptr, "expected a non-empty array of keyframes");
  std::vector<ObjectKeyframe> path;
  for (size_t i = 0; i < j.size(); ++i) {
    const std::string at = fmt::format("{}/{}", ptr, i);
    const Json& k = j[i];
    r.checkKeys(k, at, {"t", "position", "rotation_deg"});
    if (!k.contains("t")) r.fail(at, "missing key \"t\" (the keyframe's time in seconds)");
    if (k.size() < 2) r.fail(at, "a keyframe sets nothing (expected position or rotation_deg)");
    ObjectKeyframe key;
    key.t = r.number(k["t"], at + "/t");
    if (!path.empty() && !(key.t > path.back().t))
      r.fail(at + "/t", fmt::format("t {} must be greater than the previous keyframe's {}", key.t,
                                    path.back().t));
    if (k.contains("position")) key.position = r.point(k["position"], at + "/position");
    if (k.contains("rotation_deg"))
      key.rotationDeg = r.vec3(k["rotation_deg"], at + "/rotation_deg");
    path.push_back(key);
  }
  return path;
}

void readDynamicObjects(const JsonReader& r, const Json& list, Scene& scene) {
  if (!list.is_array())
    r.fail("/dynamic_objects", fmt::format("expected an array, got {}", list.type_name()));
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string ptr = fmt::format("/dynamic_objects/{}", i);
    const Json& d = list[i];
    r.checkKeys(d, ptr, {"name", "file", "transform", "rho", "path"});
    DynamicObject object;
    object.name =
        d.contains("name") ? r.string(d["name"], ptr + "/name") : fmt::format("dynamic{}", i);
    SceneBuilder builder(object.name);
    readMeshFile(r, d, ptr, builder);
    Scene mesh = builder.build();
    if (mesh.triangles.empty()) r.fail(ptr + "/file", "the file holds no triangles");
    object.mesh = std::make_shared<const Scene>(std::move(mesh));
    if (d.contains("rho")) object.rho = r.color(d["rho"], ptr + "/rho", "rho", 0.0, 1.0);
    if (d.contains("path")) object.path = readObjectPath(r, d["path"], ptr + "/path");
    scene.dynamicObjects.push_back(std::move(object));
  }
}

// A material's coverage keys (Material): "alpha", "alpha_cutoff" and "transmission" in [0, 1],
// "alpha_mode" "opaque", "mask" or "blend"; a mode that reads alpha takes it from the base colour
// texture's alpha too where the files gave no alpha texture.
void readCoverage(const JsonReader& r, const Json& m, const std::string& ptr, Material& mat) {
  auto unit = [&](const char* key, float& out) {
    if (!m.contains(key)) return;
    const double v = r.number(m[key], ptr + "/" + key);
    if (!(v >= 0.0 && v <= 1.0)) r.fail(ptr + "/" + key, fmt::format("{} out of range [0, 1]", v));
    out = float(v);
  };
  unit("alpha", mat.alpha);
  unit("alpha_cutoff", mat.alphaCutoff);
  unit("transmission", mat.transmission);
  if (!m.contains("alpha_mode")) return;
  const std::string mode = r.string(m["alpha_mode"], ptr + "/alpha_mode");
  const AlphaMode modes[] = {AlphaMode::Opaque, AlphaMode::Mask, AlphaMode::Blend};
  const auto it = std::find_if(std::begin(modes), std::end(modes),
                               [&](AlphaMode a) { return mode == alphaModeName(a); });
  if (it == std::end(modes))
    r.fail(ptr + "/alpha_mode",
           fmt::format("{} is not \"opaque\", \"mask\" or \"blend\"", quotedToken(mode)));
  mat.alphaMode = *it;
  if (mat.alphaMode != AlphaMode::Opaque && !mat.alphaTexture) mat.alphaTexture = mat.rhoTexture;
}

// Each entry overrides the files' materials of its name, or, when a geometry entry assigns it
// (`assigned`), is a material of its own (rho 0.5 unless it says).
void readMaterials(const JsonReader& r, const Json& j, const std::set<std::string>& assigned,
                   Scene& scene) {
  r.requireObject(j, "/materials");
  for (const auto& item : j.items()) {
    const std::string& name = item.key();
    const Json& m = item.value();
    const std::string ptr = "/materials/" + name;
    r.checkKeys(
        m, ptr,
        {"rho", "emission", "two_sided", "alpha", "alpha_mode", "alpha_cutoff", "transmission"});
    const bool inFiles = std::any_of(scene.materials.begin(), scene.materials.end(),
                                     [&](const Material& mat) { return mat.name == name; });
    if (!inFiles && assigned.count(name)) scene.materials.push_back({name, Color(0.5f)});
    bool found = false;
    for (Material& mat : scene.materials) {
      if (mat.name != name) continue;
      found = true;
      if (m.contains("rho")) mat.rho = r.color(m["rho"], ptr + "/rho", "rho", 0.0, 1.0);
      if (m.contains("emission"))
        mat.emission = r.color(m["emission"], ptr + "/emission", "emission", 0.0, kMaxLight);
      if (m.contains("two_sided")) mat.twoSided = r.boolean(m["two_sided"], ptr + "/two_sided");
      readCoverage(r, m, ptr, mat);
    }
    if (!found) {
      std::set<std::string> names;
      for (const Material& mat : scene.materials) names.insert(mat.name);
      r.fail(ptr, fmt::format("no material named {} in the geometry (available: {}; or assign "
                              "it to a geometry entry with \"material\")",
                              quotedToken(name), fmt::join(names, ", ")));
    }
  }
}

Vec3 readDirection(const JsonReader& r, const Json& j, const std::string& ptr) {
  const Vec3 d = r.vec3(j, ptr);
  const float len = glm::length(d);
  if (!(len > 1e-12f)) r.fail(ptr, "direction has zero length (expected a non-zero vector)");
  return d / len;
}

// A light's keyframes: t strictly increasing, each setting at least one field the light's type
// has (a point light no direction; an IES light's intensity comes from its file).
std::vector<LightKeyframe> readPath(const JsonReader& r, const Json& j, const std::string& ptr,
                                    LightType type) {
  if (!j.is_array() || j.empty())
    r.fail(ptr, fmt::format("expected a non-empty array of keyframes, got {}", brief(j)));
  std::vector<LightKeyframe> path;
  for (size_t i = 0; i < j.size(); ++i) {
    const std::string at = fmt::format("{}/{}", ptr, i);
    const Json& k = j[i];
    if (type == LightType::Point)
      r.checkKeys(k, at, {"t", "position", "intensity"});
    else if (type == LightType::Directional)
      r.checkKeys(k, at, {"t", "direction", "irradiance"});
    else if (type == LightType::Spot)
      r.checkKeys(k, at, {"t", "position", "direction", "intensity"});
    else
      r.checkKeys(k, at, {"t", "position", "direction"});
    if (!k.contains("t")) r.fail(at, "missing key \"t\" (the keyframe's time in seconds)");
    if (k.size() < 2)
      r.fail(at, "a keyframe sets nothing (expected position, direction or intensity)");
    LightKeyframe key;
    key.t = r.number(k["t"], at + "/t");
    if (!path.empty() && !(key.t > path.back().t))
      r.fail(at + "/t", fmt::format("t {} must be greater than the previous keyframe's {}", key.t,
                                    path.back().t));
    if (k.contains("position")) key.position = r.point(k["position"], at + "/position");
    if (k.contains("direction"))
      key.direction = readDirection(r, k["direction"], at + "/direction");
    if (k.contains("intensity"))
      key.intensity = r.color(k["intensity"], at + "/intensity", "intensity", 0.0, kMaxLight);
    if (k.contains("irradiance"))
      key.intensity = r.color(k["irradiance"], at + "/irradiance", "irradiance", 0.0, kMaxLight);
    path.push_back(key);
  }
  return path;
}

// A light's "group": a name that --group NAME=SCALE can give.
std::string readGroupName(const JsonReader& r, const Json& j, const std::string& ptr) {
  std::string group = r.string(j, ptr);
  if (group.empty() || group.find_first_of("=,") != std::string::npos)
    r.fail(ptr,
           fmt::format("group name {} must be non-empty, without '=' or ','", quotedToken(group)));
  return group;
}

// How strong a light is, by exactly one of its radiometric key or photometric ones (179 lm/W, as
// candela are read everywhere): a point or spot light's "intensity" (W/sr), "intensity_cd" or
// "flux_lm" (its power over the sphere, or over the spot's profile), a directional light's
// "irradiance" (W/unit^2) or "illuminance_lux" (which needs the scene's unit). A photometric
// value is a number (white) or an RGB triple.
// W per square scene unit per lux: lux is lm per square metre, so the scene's unit must be known.
double irradiancePerLux(const JsonReader& r, const std::string& at, const LengthUnit& unit) {
  if (!unit.known())
    r.fail(at,
           "lux is per square metre: the scene needs its \"unit\" (or give \"irradiance\" in "
           "W per square scene unit)");
  return kWattsPerSquareMetrePerLux * unit.metres * unit.metres;
}

// A photometric value in the engine's radiometric units (`factor` of them each), within the
// bound a scene file's light keeps (kMaxLight).
Color radiometricOf(const JsonReader& r, const std::string& at, const Color& value, double factor) {
  const Color converted = value * float(factor);
  if (!(maxComponent(converted) < kMaxLight))
    r.fail(at, fmt::format("{:g} in radiometric units must be below {:g}", maxComponent(converted),
                           kMaxLight));
  return converted;
}

Color readStrength(const JsonReader& r, const Json& j, const std::string& ptr, const Light& light,
                   const LengthUnit& unit) {
  const bool directional = !light.positional();
  const std::vector<const char*> keys =
      directional ? std::vector<const char*>{"irradiance", "illuminance_lux"}
                  : std::vector<const char*>{"intensity", "intensity_cd", "flux_lm"};
  const char* given = nullptr;
  for (const char* key : keys)
    if (j.contains(key)) {
      if (given) r.fail(ptr, fmt::format("both \"{}\" and \"{}\": give one", given, key));
      given = key;
    }
  if (!given)
    r.fail(ptr, fmt::format("missing key \"{}\" for a {} light (or \"{}\")", keys[0],
                            lightTypeName(light.type),
                            fmt::join(keys.begin() + 1, keys.end(), "\" or \"")));
  const std::string at = ptr + "/" + given;
  const Json& v = j[given];
  if (given == keys[0]) return r.color(v, at, given, 0.0, kMaxLight);
  const Color photometric =
      v.is_number() ? Color(float(r.number(v, at))) : r.color(v, at, given, 0.0, kMaxLight);
  if (!(minComponent(photometric) >= 0.0f)) r.fail(at, "must be >= 0");
  if (directional) return radiometricOf(r, at, photometric, irradiancePerLux(r, at, unit));
  if (std::string_view(given) == "intensity_cd")
    return radiometricOf(r, at, photometric, kWattsPerSrPerCandela);
  Light unitLight = light;  // flux: the power of the light at 1 W/sr, in steradians
  unitLight.intensity = Color(1.0f);
  return radiometricOf(r, at, photometric, kWattsPerSrPerCandela / unitLight.power().g);
}

Light readLight(const JsonReader& r, const Json& j, const std::string& ptr,
                const LengthUnit& unit) {
  r.requireObject(j, ptr);
  if (!j.contains("type"))
    r.fail(ptr, "missing key \"type\" (point, spot, ies, directional or sun)");
  const std::string type = r.string(j["type"], ptr + "/type");
  Light light;
  if (type == "directional") {
    r.checkKeys(
        j, ptr,
        {"type", "direction", "irradiance", "illuminance_lux", "spin_deg_per_s", "path", "group"});
    light.type = LightType::Directional;
  } else if (type == "point") {
    r.checkKeys(j, ptr,
                {"type", "position", "intensity", "intensity_cd", "flux_lm", "path", "group"});
    light.type = LightType::Point;
  } else if (type == "spot") {
    r.checkKeys(j, ptr,
                {"type", "position", "direction", "intensity", "intensity_cd", "flux_lm",
                 "inner_angle_deg", "outer_angle_deg", "spin_deg_per_s", "path", "group"});
    light.type = LightType::Spot;
  } else if (type == "ies") {
    r.checkKeys(j, ptr,
                {"type", "file", "position", "direction", "scale", "color", "spin_deg_per_s",
                 "path", "group"});
    light.type = LightType::Ies;
  } else {
    r.fail(ptr + "/type", fmt::format("unknown light type {} (expected point, spot, ies, "
                                      "directional or sun)",
                                      quotedToken(type)));
  }
  auto required = [&](const char* key) -> const Json& {
    if (!j.contains(key)) r.fail(ptr, fmt::format("missing key \"{}\" for a {} light", key, type));
    return j[key];
  };
  if (light.positional()) light.position = r.point(required("position"), ptr + "/position");
  if (!light.positional() || j.contains("direction"))
    light.direction = readDirection(r, required("direction"), ptr + "/direction");
  if (j.contains("spin_deg_per_s"))
    light.spinDegPerS = r.vec3(j["spin_deg_per_s"], ptr + "/spin_deg_per_s");
  if (j.contains("path")) light.path = readPath(r, j["path"], ptr + "/path", light.type);
  if (j.contains("group")) light.group = readGroupName(r, j["group"], ptr + "/group");
  if (light.type == LightType::Spot) {
    light.innerAngleDeg = float(r.number(required("inner_angle_deg"), ptr + "/inner_angle_deg"));
    light.outerAngleDeg = float(r.number(required("outer_angle_deg"), ptr + "/outer_angle_deg"));
    if (!(light.innerAngleDeg > 0.0f && light.innerAngleDeg <= light.outerAngleDeg &&
          light.outerAngleDeg < 180.0f))
      r.fail(ptr,
             fmt::format("spot angles inner {} / outer {} must satisfy 0 < inner <= outer < 180",
                         light.innerAngleDeg, light.outerAngleDeg));
  }
  if (light.type != LightType::Ies) light.intensity = readStrength(r, j, ptr, light, unit);
  if (light.type == LightType::Ies) {
    light.iesFile =
        resolvePath(parentDirectory(r.path()), r.string(required("file"), ptr + "/file"));
    light.ies = std::make_shared<const IesProfile>(loadIesProfile(light.iesFile));
    double scale = kWattsPerSrPerCandela;  // when the file gives no "scale"
    if (j.contains("scale")) {
      scale = r.number(j["scale"], ptr + "/scale");
      if (!(scale > 0.0))
        r.fail(ptr + "/scale", fmt::format("scale {} must be > 0 (W/sr per cd)", scale));
    }
    const Color color = j.contains("color")
                            ? r.color(j["color"], ptr + "/color", "color", 0.0, INFINITY)
                            : Color(1.0f);
    light.intensity = color * float(scale);
  }
  return light;
}

Camera readCamera(const JsonReader& r, const Json& j) {
  const std::string ptr = "/camera";
  r.checkKeys(j, ptr, {"eye", "target", "up", "fov_deg", "width", "height"});
  Camera c;
  if (j.contains("eye")) c.eye = r.point(j["eye"], ptr + "/eye");
  if (j.contains("target")) c.target = r.point(j["target"], ptr + "/target");
  if (j.contains("up")) c.up = readDirection(r, j["up"], ptr + "/up");
  if (j.contains("fov_deg")) {
    c.fovDeg = float(r.number(j["fov_deg"], ptr + "/fov_deg"));
    if (!(c.fovDeg > 0.0f && c.fovDeg < 180.0f))
      r.fail(ptr + "/fov_deg", fmt::format("fov_deg {} out of range (0, 180)", c.fovDeg));
  }
  if (j.contains("width")) c.width = int(r.integer(j["width"], ptr + "/width", 1, 65536));
  if (j.contains("height")) c.height = int(r.integer(j["height"], ptr + "/height", 1, 65536));
  if (const std::string why = cameraProblem(c); !why.empty()) {
    const size_t colon = why.find(": ");
    r.fail(ptr + "/" + why.substr(0, colon), why.substr(colon + 2));
  }
  return c;
}

// A value of the "solver" object as its declaration reads it: integers for Integer settings
// (16.0 too), doubles for Number ones. A value of the wrong kind is kept as it is, for the
// declaration to refuse with its message.
// A "solver" value as JSON types it: which setting it is and whether its value is valid is
// judged where the settings are resolved (resolveMethodSettings), against the table of the
// registered methods' settings.
SettingValue settingValue(const JsonReader& r, const Json& j, const std::string& ptr) {
  if (j.is_boolean()) return j.get<bool>();
  if (j.is_string()) return j.get<std::string>();
  if (!j.is_number()) r.fail(ptr, fmt::format("expected a value, got {}", j.type_name()));
  if (j.is_number_unsigned())
    return int64_t(std::min<uint64_t>(j.get<uint64_t>(), uint64_t(INT64_MAX)));
  if (j.is_number_integer()) return j.get<int64_t>();
  const double v = j.get<double>();
  if (!std::isfinite(v)) r.fail(ptr, "expected a finite number");
  return v;
}

SolverSettings readSolver(const JsonReader& r, const Json& j) {
  const std::string ptr = "/solver";
  r.requireObject(j, ptr);
  SolverSettings s;
  for (const auto& [key, value] : j.items())
    s.values[key] = settingValue(r, value, ptr + "/" + key);
  return s;
}

Json parseJson(const std::string& text, const std::string& path) {
  if (const std::optional<size_t> deep = jsonNestingOverflow(text))
    throw InputError(fmt::format("{}:{}", path, textPosition(text, *deep)),
                     fmt::format("JSON nested deeper than {} levels", kMaxJsonNesting));
  try {
    return Json::parse(text);
  } catch (const Json::exception& e) {
    // nlohmann reports a byte offset (1-based, just past the error) for syntax errors; a number
    // too large for a double (out_of_range 406) comes without one.
    std::string what = e.what();
    if (const size_t colon = what.find("] "); colon != std::string::npos)
      what = what.substr(colon + 2);
    if (const auto* parse = dynamic_cast<const Json::parse_error*>(&e)) {
      if (const size_t colon = what.find(": "); colon != std::string::npos)
        what = what.substr(colon + 2);
      const size_t end = parse->byte == 0 ? 0 : parse->byte - 1;
      throw InputError(fmt::format("{}:{}", path, textPosition(text, end)),
                       "invalid JSON: " + what);
    }
    throw InputError(path, "invalid JSON: " + what);
  }
}

// The sun at a place and time (sun_position.h): a directional light coming from where the sun
// stands, with the clear-sky direct light of that elevation unless "irradiance" or
// "illuminance_lux" says how much. "north" is the scene's; its own "up" (the key it had before
// the scene's) must be the scene's "up" and gives it where the scene does not.
Light readSun(const JsonReader& r, const Json& j, const std::string& ptr, const LengthUnit& unit,
              std::optional<Vec3>& sceneUp, SceneBuilder& builder) {
  r.checkKeys(j, ptr,
              {"type", "latitude", "longitude", "datetime", "north", "up", "irradiance",
               "illuminance_lux", "group"});
  auto required = [&](const char* key) -> const Json& {
    if (!j.contains(key)) r.fail(ptr, fmt::format("missing key \"{}\" for the sun", key));
    return j[key];
  };
  const double latitude = r.number(required("latitude"), ptr + "/latitude");
  const double longitude = r.number(required("longitude"), ptr + "/longitude");
  if (!(std::abs(latitude) <= 90.0)) r.fail(ptr + "/latitude", "expected degrees in [-90, 90]");
  if (!(std::abs(longitude) <= 180.0))
    r.fail(ptr + "/longitude", "expected degrees in [-180, 180] (east positive)");
  UtcTime time;
  std::string why;
  if (!parseIsoTime(r.string(required("datetime"), ptr + "/datetime"), time, why))
    r.fail(ptr + "/datetime", why);
  if (j.contains("up")) {
    const Vec3 own = readDirection(r, j["up"], ptr + "/up");
    if (sceneUp && !(glm::dot(own, *sceneUp) > 1.0f - 1e-6f))
      r.fail(ptr + "/up", "differs from the scene's \"up\" (give it once, at the top level)");
    sceneUp = own;
  }
  const Vec3 up = sceneUp.value_or(kDefaultUp);
  Vec3 north = readDirection(r, required("north"), ptr + "/north");
  north -= glm::dot(north, up) * up;  // its horizontal part
  if (!(glm::length(north) > 1e-3f)) r.fail(ptr + "/north", "must not point along \"up\"");
  north = glm::normalize(north);

  const SunPosition sun = sunPosition(time, latitude, longitude);
  Light light;
  light.type = LightType::Directional;
  light.direction = -towardSun(sun, up, north);
  if (j.contains("group")) light.group = readGroupName(r, j["group"], ptr + "/group");
  if (j.contains("irradiance")) {
    light.intensity = r.color(j["irradiance"], ptr + "/irradiance", "irradiance", 0.0, kMaxLight);
  } else {
    const double lux = j.contains("illuminance_lux")
                           ? r.number(j["illuminance_lux"], ptr + "/illuminance_lux")
                           : clearSkySunIlluminanceLux(sun.elevationDeg);
    const std::string at = ptr + "/illuminance_lux";
    if (!(lux >= 0.0)) r.fail(at, "must be >= 0");
    light.intensity = radiometricOf(r, at, Color(float(lux)), irradiancePerLux(r, at, unit));
  }
  if (sun.elevationDeg <= 0.0) {
    builder.warn(r.path(), fmt::format("{}: the sun is {:.1f} degrees below the horizon then; it "
                                       "lights nothing",
                                       ptr, -sun.elevationDeg));
    light.intensity = Color(0.0f);
  }
  return light;
}

// The sun a CIE clear sky is drawn about: the scene's one directional light (a "sun" or
// "directional" entry), as it stands at time 0.
Vec3 towardSunOf(const JsonReader& r, const std::vector<Light>& lights, SceneBuilder& builder) {
  const Light* sun = nullptr;
  for (const Light& light : lights) {
    if (light.type != LightType::Directional) continue;
    if (sun)
      r.fail("/sky/type", "a cie-clear sky needs one sun: the scene has two directional lights");
    sun = &light;
  }
  if (!sun)
    r.fail("/sky/type",
           "a cie-clear sky is drawn about the sun: the scene needs a \"sun\" or \"directional\" "
           "light");
  if (sun->animated())
    builder.warn(r.path(),
                 "/sky: a cie-clear sky stays about the sun as it stands at time 0; it "
                 "does not follow the sun's path");
  return -sun->direction;
}

// An environment sky's map (an equirectangular EXR of radiance in W/(sr unit^2), every texel
// finite and >= 0), turned by "rotation_deg" about up (right-handed) from the middle column
// looking along -z (+y where up is along z), times "scale" (1).
void readEnvironment(const JsonReader& r, const Json& j, Light& light) {
  const std::string ptr = "/sky";
  r.checkKeys(j, ptr, {"type", "file", "rotation_deg", "scale", "group"});
  if (!j.contains("file")) r.fail(ptr, "missing key \"file\" for an environment sky");
  const std::string file =
      resolvePath(parentDirectory(r.path()), r.string(j["file"], ptr + "/file"));
  if (lowerExtension(file) != ".exr")
    r.fail(ptr + "/file", "an environment map is an equirectangular .exr file");
  Image map = readExr(file);
  for (const Color& c : map.pixels)
    if (!(minComponent(c) >= 0.0f && maxComponent(c) < kMaxLight))
      r.fail(ptr + "/file", fmt::format("{} holds a radiance outside [0, {:g})", file, kMaxLight));
  light.sky.map = std::make_shared<const Image>(std::move(map));
  const Vec3 up = light.sky.up;
  const Vec3 reference = std::abs(up.z) < 0.9f ? Vec3(0, 0, -1) : Vec3(0, 1, 0);
  Vec3 forward = glm::normalize(reference - glm::dot(reference, up) * up);
  if (j.contains("rotation_deg")) {
    const float turn = glm::radians(float(r.number(j["rotation_deg"], ptr + "/rotation_deg")));
    forward = std::cos(turn) * forward + std::sin(turn) * glm::cross(up, forward);
  }
  light.sky.forward = forward;
  double scale = 1.0;
  if (j.contains("scale")) {
    scale = r.number(j["scale"], ptr + "/scale");
    if (!(scale >= 0.0)) r.fail(ptr + "/scale", fmt::format("scale {} must be >= 0", scale));
  }
  light.intensity = radiometricOf(r, ptr + "/scale", Color(float(scale)), 1.0);
}

// "sky": light from every direction above the scene's horizon (sky.h), a light of its own light
// group ("sky" unless "group" says).
Light readSky(const JsonReader& r, const Json& j, const Vec3& up, const std::vector<Light>& lights,
              SceneBuilder& builder) {
  const std::string ptr = "/sky";
  r.requireObject(j, ptr);
  if (!j.contains("type"))
    r.fail(ptr, "missing key \"type\" (uniform, cie-overcast, cie-clear or environment)");
  const std::string type = r.string(j["type"], ptr + "/type");
  Light light;
  light.type = LightType::Sky;
  light.group = "sky";
  light.sky.up = up;
  const SkyModel models[] = {SkyModel::Uniform, SkyModel::CieOvercast, SkyModel::CieClear,
                             SkyModel::Environment};
  const auto model = std::find_if(std::begin(models), std::end(models),
                                  [&](SkyModel m) { return type == skyModelName(m); });
  if (model == std::end(models))
    r.fail(ptr + "/type", fmt::format("unknown sky type {} (expected uniform, cie-overcast, "
                                      "cie-clear or environment)",
                                      quotedToken(type)));
  light.sky.model = *model;
  if (j.contains("group")) light.group = readGroupName(r, j["group"], ptr + "/group");
  if (light.sky.model == SkyModel::Environment) {
    readEnvironment(r, j, light);
    return light;
  }
  const char* key = light.sky.model == SkyModel::Uniform ? "radiance" : "zenith_radiance";
  r.checkKeys(j, ptr, {"type", key, "group"});
  if (!j.contains(key)) r.fail(ptr, fmt::format("missing key \"{}\" for a {} sky", key, type));
  light.intensity = r.color(j[key], ptr + "/" + key, key, 0.0, kMaxLight);
  if (light.sky.model == SkyModel::CieClear) light.sky.towardSun = towardSunOf(r, lights, builder);
  return light;
}

// "unit": the length unit of the scene's coordinates (after the geometry's transforms).
LengthUnit readUnit(const JsonReader& r, const Json& j) {
  const std::string name = r.string(j, "/unit");
  const std::optional<LengthUnit> unit = lengthUnitNamed(name);
  if (!unit)
    r.fail("/unit", fmt::format("unknown unit {} (expected one of: {})", quotedToken(name),
                                fmt::join(lengthUnitNames(), ", ")));
  return *unit;
}

}  // namespace

Scene loadSceneJson(const std::string& path) {
  const Json root = parseJson(readTextFile(path, "scene file"), path);
  const JsonReader r(path);
  r.checkKeys(root, "",
              {"unit", "up", "geometry", "materials", "lights", "sky", "camera", "dynamic_objects",
               "solver", "sensors"});
  SceneBuilder builder(path);
  std::vector<MaterialAssignment> assignments;
  if (root.contains("geometry")) assignments = readGeometry(r, root["geometry"], builder);
  Scene& scene = builder.scene();
  if (root.contains("unit")) scene.unit = readUnit(r, root["unit"]);
  std::set<std::string> assigned;
  for (const MaterialAssignment& a : assignments) assigned.insert(a.material);
  if (root.contains("materials")) readMaterials(r, root["materials"], assigned, scene);
  assignMaterials(r, assignments, scene);
  if (root.contains("dynamic_objects")) readDynamicObjects(r, root["dynamic_objects"], scene);
  std::optional<Vec3> up;  // the scene's zenith, for the sun and the sky
  if (root.contains("up")) up = readDirection(r, root["up"], "/up");
  if (root.contains("lights")) {
    const Json& lights = root["lights"];
    if (!lights.is_array())
      r.fail("/lights", fmt::format("expected an array, got {}", lights.type_name()));
    for (size_t i = 0; i < lights.size(); ++i) {
      const std::string at = fmt::format("/lights/{}", i);
      const Json& light = lights[i];
      const bool sun = light.is_object() && light.value("type", Json()) == "sun";
      scene.lights.push_back(sun ? readSun(r, light, at, scene.unit, up, builder)
                                 : readLight(r, light, at, scene.unit));
    }
  }
  if (root.contains("sky"))
    scene.lights.push_back(readSky(r, root["sky"], up.value_or(kDefaultUp), scene.lights, builder));
  if (root.contains("camera")) scene.camera = readCamera(r, root["camera"]);
  if (root.contains("solver")) scene.solver = readSolver(r, root["solver"]);
  Scene built = builder.build();
  if (root.contains("sensors")) built.sensors = readSensors(r, root["sensors"]);
  return built;
}

}  // namespace rad
