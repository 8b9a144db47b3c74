#pragma once
// The scene model: triangles that remember the planar faces they came from, named objects,
// diffuse materials, analytic lights, a camera and the solver settings.
// Units and conventions: docs/ARCHITECTURE.md ("Units and conventions").

#include <radiosity/ies_profile.h>
#include <radiosity/sky.h>
#include <radiosity/texture.h>
#include <radiosity/types.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace rad {

/// How a material's alpha (its factor, the base colour texture's alpha, the vertices' alpha)
/// covers its surface, as glTF's alphaMode: Opaque ignores alpha; Mask keeps the points whose
/// alpha reaches the cutoff and cuts the rest away; Blend covers a share alpha of every point
/// (the rest lets light through).
enum class AlphaMode : uint8_t { Opaque, Mask, Blend };
/// "opaque", "mask" or "blend", as the scene file spells it.
const char* alphaModeName(AlphaMode mode);

/// A Lambertian material. Faces are one-sided (front = counter-clockwise side) unless twoSided.
/// A texture multiplies its factor where the scene has texture coordinates (Scene::texcoords).
/// Where it is not opaque, a point x of its surface has a coverage c(x) in [0, 1]
/// (Scene::coverageAt): the share of light arriving there that meets the surface (reflected by
/// rho, absorbed, or emitted from it: c E leaves a unit of area); the rest passes straight on.
struct Material {
  std::string name;
  Color rho{0.5f};       ///< diffuse reflectance per channel, in [0, 1)
  Color emission{0.0f};  ///< Ke: emitted radiance from the front; radiosity E = pi * Ke
  bool twoSided = false;
  TextureMap rhoTexture{};       ///< base colour (glTF baseColorTexture, OBJ map_Kd)
  TextureMap emissionTexture{};  ///< emission (glTF emissiveTexture, OBJ map_Ke)
  /// The texture whose alpha channel multiplies alpha: glTF's base colour texture, OBJ map_d.
  TextureMap alphaTexture{};
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alpha = 1.0f;        ///< glTF baseColorFactor's alpha, OBJ d; in [0, 1]
  float alphaCutoff = 0.5f;  ///< Mask: alpha below it is cut away
  /// Thin transmission (glTF KHR_materials_transmission): the share in [0, 1] of the light that
  /// passes straight through every point; the rest meets the surface as its alpha says.
  float transmission = 0.0f;

  bool emits() const { return maxComponent(emission) > 0.0f; }
  /// True when the coverage is 1 everywhere whatever the textures and vertices say.
  bool opaque() const { return alphaMode == AlphaMode::Opaque && !(transmission > 0.0f); }
};

/// A named group of faces: an OBJ `o`/`g`, a glTF node, a built-in scene part.
struct SceneObject {
  std::string name;
};

/// One planar polygon of the input, kept so that the patch mesher can subdivide faces, not
/// triangles. Its triangles are Scene::triangles[firstTriangle, firstTriangle + triangleCount).
struct Face {
  uint32_t object = 0;
  uint32_t material = 0;
  uint32_t firstTriangle = 0;
  uint32_t triangleCount = 0;
  std::vector<uint32_t> corners;  ///< polygon corners (indices into Scene::positions), CCW
  Vec3 normal{0.0f};              ///< unit normal of the front side
  float area = 0.0f;
};

/// Object: one axis lobe of the light a dynamic object reflects, leaving from the centroid of its
/// faces that send it (lighting/dynamic_objects.h; made by the program, not read from scene
/// files). Directional: light from so far away that its rays are parallel (the sun). Sky: light
/// from every direction above the horizon, from beyond the scene (sky.h).
enum class LightType { Point, Spot, Ies, Object, Directional, Sky };
/// "point", "spot", "ies", "object", "directional" or "sky", as the scene file and the stats
/// spell it.
const char* lightTypeName(LightType type);

/// A light's state at a time of its animation: the fields it sets (the others follow the
/// keyframes around it that set them, or stay the light's own).
struct LightKeyframe {
  double t = 0.0;  ///< seconds
  std::optional<Vec3> position, direction;
  std::optional<Color> intensity;
  bool operator==(const LightKeyframe&) const = default;
};

/// max(0, d . e_k) for the axes e_k = +x, -x, +y, -y, +z, -z (k = 0..5): how much of lobe k of
/// an Object light points along d, or how much of a surface with normal d faces e_k.
inline float axisLobe(const Vec3& d, int k) {
  return std::max(0.0f, (k % 2 == 0 ? 1.0f : -1.0f) * d[k / 2]);
}

/// An analytic light. At a point (point, spot, IES, object), `intensity` is radiant intensity in
/// W/sr (RGB): the irradiance at distance d on a surface tilted by theta is I cos(theta) / d^2.
/// A directional light has no position: it travels along `direction`, and `intensity` is the
/// irradiance E (W per square scene unit) on a plane facing it, E cos(theta) on one tilted by
/// theta, wherever nothing shadows it. A sky has no position either: `intensity` is its reference
/// radiance (W/(sr unit^2): a uniform sky's, a CIE sky's at the zenith) and `sky` its shape.
struct Light {
  LightType type = LightType::Point;
  Vec3 position{0.0f};
  /// Unit; the axis of a spot or IES light, the way a directional light's light travels.
  Vec3 direction{0.0f, -1.0f, 0.0f};
  /// W/sr on the axis (spot) or in every direction (point); directional: irradiance, W/unit^2.
  Color intensity{0.0f};
  float innerAngleDeg = 0.0f;  ///< spot: full intensity inside this half-angle
  float outerAngleDeg = 0.0f;  ///< spot: zero outside this half-angle, smooth between
  /// Animation: the direction's angular velocity (degrees/s about the vector's axis, by the
  /// right-hand rule; a spot with [0, 90, 0] turns a quarter turn a second about +y).
  Vec3 spinDegPerS{0.0f};
  /// Animation: keyframes by increasing t; positions and intensities are interpolated linearly,
  /// directions along the great circle (spherically); before the first and after the last
  /// keyframe a field holds its value. The spin turns the direction the path gives.
  std::vector<LightKeyframe> path;
  /// The light group it belongs to (light_groups.h); empty: a group of its own.
  std::string group;
  /// IES: the photometric table, and the W/sr per candela applied to it (`intensity` is the
  /// colour-weighted scale: intensity * candela gives W/sr).
  std::shared_ptr<const IesProfile> ies;
  std::string iesFile;
  /// Object: toward unit direction d it sends sum_k lobes[k] max(0, d . e_k) W/sr, e_k the axes
  /// +x, -x, +y, -y, +z, -z (a diffuse object's faces seen from d, summarized by axis).
  std::array<Color, 6> lobes{};
  /// Object: the radius around `position` that the object's own surface lies within. Shadow
  /// rays toward the light stop there: the light leaves that surface, which must not shadow it.
  float radius = 0.0f;
  /// Sky: the shape of its radiance over the directions.
  Sky sky;

  /// Radiant intensity (W/sr) toward the unit direction `toward` (from the light outward); for a
  /// sky, the radiance travelling along `toward` (arriving from -toward).
  Color intensityToward(const Vec3& toward) const;
  /// Total radiant power (W) the light emits in all directions; 0 for a directional light or a
  /// sky, whose power is that of the scene it falls on (Scene::lightPower).
  Color power() const;
  /// False for a directional light and a sky, which have no position.
  bool positional() const { return type != LightType::Directional && type != LightType::Sky; }
  /// True if the light moves or changes with time (a spin or a path).
  bool animated() const { return !path.empty() || spinDegPerS != Vec3(0.0f); }
  /// The light at `seconds` into its animation (itself when it has none).
  Light at(double seconds) const;
  /// Every field equal (the same IES profile object).
  bool operator==(const Light&) const = default;
};

struct Scene;

/// A moving object's placement at a time of its path: the fields it sets (the others follow the
/// keyframes around it that set them).
struct ObjectKeyframe {
  double t = 0.0;                   ///< seconds
  std::optional<Vec3> position;     ///< where its own origin goes, scene units
  std::optional<Vec3> rotationDeg;  ///< about its origin: x, then y, then z (degrees)
  bool operator==(const ObjectKeyframe&) const = default;
};

/// An object that moves: it takes no part in the static solve (form factors, voxels); it is lit
/// by probes of the static solution and drawn in pictures (lighting/dynamic_objects.h).
struct DynamicObject {
  std::string name;
  std::shared_ptr<const Scene> mesh;  ///< its triangles and materials, in its own frame
  std::optional<Color> rho;           ///< a reflectance for all of it, in place of its materials'
  /// Keyframes by increasing t, interpolated linearly (rotation per angle); empty: it stays.
  std::vector<ObjectKeyframe> path;
  /// Its frame in the scene at `seconds`: rotation about its origin, then the move.
  glm::mat4 placementAt(double seconds) const;
};

/// A pinhole camera; fovDeg is the vertical field of view.
struct Camera {
  Vec3 eye{0.0f, 0.0f, 1.0f};
  Vec3 target{0.0f};
  Vec3 up{0.0f, 1.0f, 0.0f};
  float fovDeg = 40.0f;
  int width = 512;
  int height = 512;
};

/// Why `camera` gives no view, naming the field at fault ("target: eye and target coincide",
/// "up: up is zero or parallel to the viewing direction"), or "" when it gives one.
std::string cameraProblem(const Camera& camera);

/// A value of the scene's "solver" object or of a flag, checked against its declaration
/// (solver_settings.h).
using SettingValue = std::variant<bool, int64_t, double, std::string>;

/// The scene's "solver" object: its values by key (solver_settings.h declares the keys). A
/// command-line flag wins over it, and a method's default applies where neither is given.
struct SolverSettings {
  std::map<std::string, SettingValue, std::less<>> values;
};

/// A point where light is measured, as a lighting designer's sensor (a lux meter) lies: its
/// position and the unit normal of the plane it measures on (irradiance counts light from the
/// hemisphere the normal points into).
struct SensorPoint {
  Vec3 position{0.0f};
  Vec3 normal{0.0f, 1.0f, 0.0f};
};

/// A named set of sensors: one point, a calculation grid (a work plane's) or a file's rows.
struct SensorSet {
  std::string name;
  std::vector<SensorPoint> points;
};

/// A scene's length unit: what one scene unit is in metres. Emission Ke is radiance per square
/// scene unit (W/(sr unit^2)) and irradiance W per square scene unit; the unit converts them to
/// SI. Unknown for an OBJ alone and a scene file that does not say ("unit").
struct LengthUnit {
  std::string name;     ///< "mm", "cm", "m", "in" or "ft"; empty when unknown
  double metres = 0.0;  ///< metres per scene unit; 0 when unknown
  bool known() const { return metres > 0.0; }
  /// The name, or "scene unit" when unknown.
  std::string symbol() const { return known() ? name : "scene unit"; }
};

/// The unit of that name ("mm", "cm", "m", "in", "ft"), or nullopt.
std::optional<LengthUnit> lengthUnitNamed(std::string_view name);
/// The names lengthUnitNamed knows, for messages.
std::vector<std::string> lengthUnitNames();

struct Scene {
  std::string name;  ///< built-in name or file path
  LengthUnit unit;   ///< built-in scenes and glTF files know theirs (glTF: metres)
  std::vector<Vec3> positions;
  /// Texture coordinates, one per position, or none (a textured material then uses its
  /// texture's mean).
  std::vector<Vec2> texcoords;
  /// Vertex colours' alpha (glTF COLOR_0), one per position, or none (1 everywhere).
  std::vector<float> vertexAlpha;
  std::vector<UVec3> triangles;        ///< CCW about the front normal
  std::vector<uint32_t> triangleFace;  ///< face of each triangle
  std::vector<Face> faces;
  std::vector<SceneObject> objects;
  std::vector<Material> materials;
  std::vector<Light> lights;
  std::vector<DynamicObject> dynamicObjects;
  std::optional<Camera> camera;  ///< none: the renderer frames the scene's bounds
  /// The cameras the geometry files carry (glTF), in file order, by name ("camera<i>" when a
  /// file gives none). The first is `camera` unless the scene file sets one.
  std::vector<std::pair<std::string, Camera>> cameras;
  SolverSettings solver;
  std::vector<SensorSet> sensors;     ///< where the scene file asks for the light (sensors.h)
  std::vector<std::string> warnings;  ///< non-fatal problems found while loading

  const Face& faceOf(uint32_t triangle) const { return faces[triangleFace[triangle]]; }
  const Material& materialOf(uint32_t triangle) const {
    return materials[faceOf(triangle).material];
  }
  Vec3 triangleNormal(uint32_t triangle) const;  ///< unit geometric normal (front side)
  float triangleArea(uint32_t triangle) const;
  /// Texture coordinates at barycentric (u, v) of a triangle (its point (1-u-v) p0 + u p1 +
  /// v p2); (0, 0) in a scene without them.
  Vec2 texcoordAt(uint32_t triangle, Vec2 barycentric) const;
  /// A texture of the triangle's material at a point of it, averaged over `footprint` scene
  /// units (0: a texel); 1 for no texture, its mean in a scene without texture coordinates.
  Color textureAt(const TextureMap& map, uint32_t triangle, Vec2 barycentric,
                  float footprint = 0.0f) const;
  /// Reflectance rho at a point of a triangle: its material's factor times the texture there;
  /// emission Ke likewise.
  Color reflectanceAt(uint32_t triangle, Vec2 barycentric, float footprint = 0.0f) const;
  Color emissionAt(uint32_t triangle, Vec2 barycentric, float footprint = 0.0f) const;
  /// Coverage c in [0, 1] at a point of a triangle (Material): 1 for an opaque material; Mask
  /// thresholds the alpha at the point itself (footprint 0, whatever is given: a mean over a
  /// region is coverageMean's), Blend takes alpha averaged over the footprint; times
  /// (1 - transmission).
  float coverageAt(uint32_t triangle, Vec2 barycentric, float footprint = 0.0f) const;
  /// The coverage's mean over a triangle (its value at 64 points, the centroids of the triangle
  /// cut into 8 x 8; the one value where it is uniform).
  float coverageMean(uint32_t triangle) const;
  /// A face's area times its mean coverage: the area that emits and reflects.
  double coveredArea(const Face& face) const;
  /// True if the triangle's coverage is the same at all of its points (its material's alpha
  /// reads no texture alpha and no vertex alpha, or it is opaque).
  bool uniformCoverage(uint32_t triangle) const;
  /// True if some material is not opaque: ray queries and the solvers take coverage into account.
  bool hasCoverage() const;
  /// The barycentrics (u, v) of a point on a triangle's plane (projected onto it).
  Vec2 barycentricOf(uint32_t triangle, const Vec3& point) const;
  /// The point's barycentrics on the triangle of `face` that holds it (the nearest where none
  /// does, a point just off the face's outline); the triangle goes into `triangle`.
  Vec2 locateOnFace(uint32_t face, const Vec3& point, uint32_t& triangle) const;
  /// The same among triangles [first, first + count) of a face (a part of it a caller knows
  /// the point lies on: a face of thousands of triangles costs as many tests).
  Vec2 locateOnTriangles(uint32_t first, uint32_t count, const Vec3& point,
                         uint32_t& triangle) const;
  Bounds bounds() const;
  /// Total emitted power (W): pi * Ke * area * mean coverage over emitting triangles plus every
  /// light's lightPower.
  Color emittedPower() const;
  /// A light's power (W): Light::power(), and for a directional light or a sky the power it
  /// sends through the scene's bounds (the irradiance times the area of the bounding box's
  /// shadow on a plane facing it, summed over the sky's directions), what can fall on the scene.
  Color lightPower(const Light& light) const;
  bool hasEmitters() const;
  /// The camera of the scene, or one that frames its bounds from the front (+z looking -z).
  Camera cameraOrDefault() const;
  /// The lights at `seconds` into their animation (Light::at).
  std::vector<Light> lightsAt(double seconds) const;
  /// The scene with its dynamic objects placed as at `seconds`, their triangles after its own
  /// (its own triangles, faces, objects and materials keep their indices), and no dynamic
  /// objects: what a picture casts camera and shadow rays against.
  Scene withDynamicObjectsAt(double seconds) const;
  /// Triangles of the scene's own (the static ones), in a scene withDynamicObjectsAt made.
  uint32_t staticTriangles = UINT32_MAX;

 private:
  /// A footprint in scene units on a triangle in its texture's units (the scene has coordinates).
  float textureFootprint(uint32_t triangle, float footprint) const;
};

}  // namespace rad
