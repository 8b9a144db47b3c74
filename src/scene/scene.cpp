#include <radiosity/scene.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <limits>

namespace rad {

namespace {

// The one table of length units a scene can be in.
const LengthUnit kLengthUnits[] = {
    {"mm", 0.001}, {"cm", 0.01}, {"m", 1.0}, {"in", 0.0254}, {"ft", 0.3048}};

}  // namespace

std::optional<LengthUnit> lengthUnitNamed(std::string_view name) {
  for (const LengthUnit& u : kLengthUnits)
    if (u.name == name) return u;
  return std::nullopt;
}

std::vector<std::string> lengthUnitNames() {
  std::vector<std::string> names;
  for (const LengthUnit& u : kLengthUnits) names.push_back(u.name);
  return names;
}

Vec3 Scene::triangleNormal(uint32_t t) const {
  const UVec3& tri = triangles[t];
  const Vec3d a = positions[tri.x], b = positions[tri.y], c = positions[tri.z];
  return Vec3(glm::normalize(glm::cross(b - a, c - a)));
}

float Scene::triangleArea(uint32_t t) const {
  const UVec3& tri = triangles[t];
  const Vec3d a = positions[tri.x], b = positions[tri.y], c = positions[tri.z];
  return float(0.5 * glm::length(glm::cross(b - a, c - a)));
}

Vec2 Scene::texcoordAt(uint32_t t, Vec2 b) const {
  if (texcoords.empty()) return Vec2(0.0f);
  const UVec3& tri = triangles[t];
  return (1.0f - b.x - b.y) * texcoords[tri.x] + b.x * texcoords[tri.y] + b.y * texcoords[tri.z];
}

// The footprint in scene units becomes one in texture units by the triangle's own scale (the
// square root of its areas' ratio).
float Scene::textureFootprint(uint32_t t, float footprint) const {
  const UVec3& tri = triangles[t];
  const Vec2 e1 = texcoords[tri.y] - texcoords[tri.x], e2 = texcoords[tri.z] - texcoords[tri.x];
  const float uvArea = 0.5f * std::abs(e1.x * e2.y - e1.y * e2.x);
  const float area = triangleArea(t);
  const float scale = area > 0.0f ? std::sqrt(uvArea / area) : 0.0f;
  return footprint * scale;
}

Color Scene::textureAt(const TextureMap& map, uint32_t t, Vec2 b, float footprint) const {
  if (!map) return Color(1.0f);
  if (texcoords.empty()) return map.texture->mean();
  return map.at(texcoordAt(t, b), textureFootprint(t, footprint));
}

Color Scene::reflectanceAt(uint32_t t, Vec2 b, float footprint) const {
  const Material& m = materialOf(t);
  return m.rho * textureAt(m.rhoTexture, t, b, footprint);
}

Color Scene::emissionAt(uint32_t t, Vec2 b, float footprint) const {
  const Material& m = materialOf(t);
  return m.emission * textureAt(m.emissionTexture, t, b, footprint);
}

float Scene::coverageAt(uint32_t t, Vec2 b, float footprint) const {
  const Material& m = materialOf(t);
  if (m.opaque()) return 1.0f;
  float alpha = 1.0f;
  if (m.alphaMode != AlphaMode::Opaque) {
    const float texelFootprint = m.alphaMode == AlphaMode::Mask ? 0.0f : footprint;
    alpha = m.alpha;
    if (m.alphaTexture && m.alphaTexture.texture->hasAlpha())
      alpha *= texcoords.empty()
                   ? m.alphaTexture.texture->meanAlpha()
                   : m.alphaTexture.alphaAt(texcoordAt(t, b), textureFootprint(t, texelFootprint));
    if (!vertexAlpha.empty()) {
      const UVec3& tri = triangles[t];
      alpha *= (1.0f - b.x - b.y) * vertexAlpha[tri.x] + b.x * vertexAlpha[tri.y] +
               b.y * vertexAlpha[tri.z];
    }
    alpha = m.alphaMode == AlphaMode::Mask ? (alpha >= m.alphaCutoff ? 1.0f : 0.0f)
                                           : std::clamp(alpha, 0.0f, 1.0f);
  }
  return alpha * (1.0f - m.transmission);
}

float Scene::coverageMean(uint32_t t) const {
  if (uniformCoverage(t)) return coverageAt(t, Vec2(1.0f / 3.0f));
  // The n^2 small triangles of edges cut into n: (i, j) upright and, but on the last row,
  // upside down, their centroids at (i + 1/3, j + 1/3) / n and (i + 2/3, j + 2/3) / n.
  constexpr int n = 8;
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; i + j < n; ++j) {
      sum += coverageAt(t, Vec2(float(i) + 1.0f / 3.0f, float(j) + 1.0f / 3.0f) / float(n));
      if (i + j < n - 1)
        sum += coverageAt(t, Vec2(float(i) + 2.0f / 3.0f, float(j) + 2.0f / 3.0f) / float(n));
    }
  return float(sum / double(n * n));
}

double Scene::coveredArea(const Face& f) const {
  if (materials[f.material].opaque()) return f.area;
  double area = 0.0;
  for (uint32_t t = f.firstTriangle; t < f.firstTriangle + f.triangleCount; ++t)
    area += double(triangleArea(t)) * coverageMean(t);
  return area;
}

bool Scene::uniformCoverage(uint32_t t) const {
  const Material& m = materialOf(t);
  if (m.alphaMode == AlphaMode::Opaque) return true;
  const bool texelAlpha =
      m.alphaTexture && m.alphaTexture.texture->hasAlpha() && !texcoords.empty();
  return !texelAlpha && vertexAlpha.empty();
}

bool Scene::hasCoverage() const {
  return std::any_of(materials.begin(), materials.end(),
                     [](const Material& m) { return !m.opaque(); });
}

const char* alphaModeName(AlphaMode mode) {
  switch (mode) {
    case AlphaMode::Mask:
      return "mask";
    case AlphaMode::Blend:
      return "blend";
    case AlphaMode::Opaque:
      break;
  }
  return "opaque";
}

Vec2 Scene::barycentricOf(uint32_t t, const Vec3& point) const {
  const UVec3& tri = triangles[t];
  const Vec3d a = positions[tri.x], e1 = Vec3d(positions[tri.y]) - a,
              e2 = Vec3d(positions[tri.z]) - a, p = Vec3d(point) - a;
  // In the triangle's plane (least squares: the point may lie a little off it).
  const double d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
  const double p1 = glm::dot(p, e1), p2 = glm::dot(p, e2), det = d11 * d22 - d12 * d12;
  if (!(std::abs(det) > 0.0)) return Vec2(1.0f / 3.0f);
  return Vec2(float((d22 * p1 - d12 * p2) / det), float((d11 * p2 - d12 * p1) / det));
}

Vec2 Scene::locateOnFace(uint32_t face, const Vec3& point, uint32_t& triangle) const {
  return locateOnTriangles(faces[face].firstTriangle, faces[face].triangleCount, point, triangle);
}

Vec2 Scene::locateOnTriangles(uint32_t first, uint32_t count, const Vec3& point,
                              uint32_t& triangle) const {
  float best = -std::numeric_limits<float>::infinity();
  Vec2 found(1.0f / 3.0f);
  triangle = first;
  for (uint32_t t = first; t < first + count; ++t) {
    const Vec2 b = barycentricOf(t, point);
    const float inside = std::min({b.x, b.y, 1.0f - b.x - b.y});  // >= 0 inside
    if (inside > best) {
      best = inside;
      found = b;
      triangle = t;
      if (inside >= 0.0f) break;
    }
  }
  return found;
}

Bounds Scene::bounds() const {
  Bounds b;
  for (const UVec3& t : triangles)
    for (int k = 0; k < 3; ++k) b.extend(positions[t[k]]);
  for (const Light& light : lights)
    if (light.positional()) b.extend(light.position);
  return b;
}

Color Scene::emittedPower() const {
  Vec3d power(0.0);
  for (uint32_t t = 0; t < triangles.size(); ++t) {
    const Material& m = materialOf(t);
    if (!m.emits()) continue;
    const double sides = m.twoSided ? 2.0 : 1.0;
    // A texture's emission taken at the centroid over the triangle's size: its mean there.
    const float size = std::sqrt(triangleArea(t));
    const Color ke = emissionAt(t, Vec2(1.0f / 3.0f), size);
    power += Vec3d(ke) * (glm::pi<double>() * sides * triangleArea(t) * coverageMean(t));
  }
  for (const Light& light : lights) power += Vec3d(lightPower(light));
  return Color(power);
}

namespace {

// The area of the shadow a box of edges `e` casts on a plane facing the unit direction d: each
// face pair's area times |d . its normal|.
double boxShadow(const Vec3d& e, const Vec3d& d) {
  const Vec3d a = glm::abs(d);
  return a.x * e.y * e.z + a.y * e.x * e.z + a.z * e.x * e.y;
}

// The power a sky sends into a box of edges `e`: the integral over the directions w above its
// horizon of L(w) times the box's shadow across w, by the midpoint rule in the elevation's sine
// and the azimuth (equal solid angles; 64 x 256 cells, exact to 1e-4 for the CIE skies).
Color skyPowerInto(const Light& sky, const Vec3d& e) {
  constexpr int kRings = 64, kSectors = 256;
  const Vec3 up = sky.sky.up;
  const Vec3 x =
      glm::normalize(glm::cross(std::abs(up.y) < 0.9f ? Vec3(0, 1, 0) : Vec3(1, 0, 0), up));
  const Vec3 z = glm::cross(x, up);
  const double cellSolidAngle = 2.0 * glm::pi<double>() / (double(kRings) * kSectors);
  Vec3d sum(0.0);
  for (int i = 0; i < kRings; ++i) {
    const double sinElevation = (i + 0.5) / kRings,
                 cosElevation = std::sqrt(1.0 - sinElevation * sinElevation);
    for (int k = 0; k < kSectors; ++k) {
      const double azimuth = 2.0 * glm::pi<double>() * (k + 0.5) / kSectors;
      const Vec3 w = Vec3(cosElevation * std::cos(azimuth)) * x +
                     Vec3(cosElevation * std::sin(azimuth)) * z + Vec3(float(sinElevation)) * up;
      sum += Vec3d(sky.intensityToward(-w)) * boxShadow(e, Vec3d(w));
    }
  }
  return Color(sum * cellSolidAngle);
}

}  // namespace

Color Scene::lightPower(const Light& light) const {
  if (light.positional()) return light.power();
  Bounds b;
  for (const Vec3& p : positions) b.extend(p);
  if (b.empty()) return Color(0.0f);
  const Vec3d e = Vec3d(b.max - b.min);
  if (light.type == LightType::Sky) return skyPowerInto(light, e);
  return Color(Vec3d(light.intensity) * boxShadow(e, Vec3d(light.direction)));
}

bool Scene::hasEmitters() const {
  for (uint32_t t = 0; t < triangles.size(); ++t)
    if (materialOf(t).emits()) return true;
  for (const Light& light : lights)
    if (maxComponent(lightPower(light)) > 0.0f) return true;
  return false;
}

std::string cameraProblem(const Camera& camera) {
  const Vec3 view = camera.target - camera.eye;
  if (!(glm::length(view) > 0.0f)) return "target: eye and target coincide";
  if (!(glm::length(glm::cross(glm::normalize(view), camera.up)) > 1e-6f * glm::length(camera.up)))
    return "up: up is zero or parallel to the viewing direction";
  return "";
}

Camera Scene::cameraOrDefault() const {
  if (camera) return *camera;
  Camera c;
  const Bounds b = bounds();
  if (b.empty()) return c;
  // Look along -z at the centre, far enough that the bounding sphere fits the field of view.
  const float radius = 0.5f * b.diagonal();
  const float distance = radius / std::sin(glm::radians(0.5f * c.fovDeg));
  c.target = b.center();
  c.eye = b.center() + Vec3(0.0f, 0.0f, b.extent().z * 0.5f + distance);
  return c;
}

}  // namespace rad
