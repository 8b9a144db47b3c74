#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/message_text.h>
#include <radiosity/scene_builder.h>

#include <array>
#include <cmath>
#include <glm/gtx/component_wise.hpp>
#include <optional>

#include "scene/polygon.h"

namespace rad {

namespace {

// A polygon counts as planar when no corner is farther from its plane than this fraction of
// the polygon's size: the Cornell box's red wall (3 mm warp over 550 mm) is not planar.
constexpr double kPlanarTolerance = 1e-4;

double polygonSize(std::span<const Vec3> corners) {
  Bounds b;
  for (const Vec3& c : corners) b.extend(c);
  return b.diagonal();
}

}  // namespace

SceneBuilder::SceneBuilder(std::string sceneName) {
  scene_.name = std::move(sceneName);
}

uint32_t SceneBuilder::addMaterial(Material material) {
  // A factor of 1 is common in files; the solvers need rho below 1 (a closed room of rho 1 never
  // converges), so 1 is taken as 0.999, and counted for one warning where it is the reflectance
  // itself: under a texture it is only the texture's scale (glTF's default), and the texels set
  // the reflectance.
  if (maxComponent(material.rho) == 1.0f) {
    material.rho = glm::min(material.rho, Color(kMaxReflectance));
    if (!material.rhoTexture) ++clampedMaterials_;
  }
  for (int c = 0; c < 3; ++c) {
    if (!(material.rho[c] >= 0.0f && material.rho[c] < 1.0f))
      throw InputError(scene_.name, fmt::format("material {}: rho {} must be in [0, 1]",
                                                quotedToken(material.name), material.rho[c]));
    if (!(material.emission[c] >= 0.0f && std::isfinite(material.emission[c])))
      throw InputError(scene_.name, fmt::format("material {}: emission {} must be finite and >= 0",
                                                quotedToken(material.name), material.emission[c]));
  }
  for (auto [value, what] :
       {std::pair{material.alpha, "alpha"}, std::pair{material.alphaCutoff, "alpha cutoff"},
        std::pair{material.transmission, "transmission"}})
    if (!(value >= 0.0f && value <= 1.0f))
      throw InputError(scene_.name, fmt::format("material {}: {} {} must be in [0, 1]",
                                                quotedToken(material.name), what, value));
  scene_.materials.push_back(std::move(material));
  return uint32_t(scene_.materials.size() - 1);
}

uint32_t SceneBuilder::addObject(std::string name) {
  scene_.objects.push_back({std::move(name)});
  return uint32_t(scene_.objects.size() - 1);
}

uint32_t SceneBuilder::addVertex(const Vec3& p, const std::string& where) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
    throw InputError(where, fmt::format("vertex ({}, {}, {}) is not finite", p.x, p.y, p.z));
  if (glm::compMax(glm::abs(p)) > kMaxSceneCoordinate)
    throw InputError(where, fmt::format("vertex ({}, {}, {}) is beyond {:g} scene units (after the "
                                        "file's transforms): check the scale",
                                        p.x, p.y, p.z, kMaxSceneCoordinate));
  scene_.positions.push_back(p);
  return uint32_t(scene_.positions.size() - 1);
}

uint32_t SceneBuilder::addVertex(const Vec3& p, const Vec2& texcoord, const std::string& where) {
  const uint32_t v = addVertex(p, where);
  setTexcoord(v, texcoord, where);
  return v;
}

void SceneBuilder::setTexcoord(uint32_t vertex, const Vec2& texcoord, const std::string& where) {
  if (!std::isfinite(texcoord.x) || !std::isfinite(texcoord.y))
    throw InputError(where, "texture coordinates must be finite");
  scene_.texcoords.resize(scene_.positions.size(), Vec2(0.0f));
  hasTexcoord_.resize(scene_.positions.size(), 0);
  scene_.texcoords.at(vertex) = texcoord;
  hasTexcoord_[vertex] = 1;
}

void SceneBuilder::setVertexAlpha(uint32_t vertex, float alpha, const std::string& where) {
  if (!(alpha >= 0.0f && alpha <= 1.0f))
    throw InputError(where, fmt::format("vertex colour alpha {} out of range [0, 1]", alpha));
  if (alpha == 1.0f && scene_.vertexAlpha.empty()) return;
  scene_.vertexAlpha.resize(scene_.positions.size(), 1.0f);
  scene_.vertexAlpha.at(vertex) = alpha;
}

// A textured material on faces without texture coordinates shows its texture's mean (the
// factor times it), and the scene keeps coordinates only when a texture uses them.
void SceneBuilder::resolveUnmappedTextures() {
  std::vector<uint8_t> unmapped(scene_.materials.size(), 0);
  hasTexcoord_.resize(scene_.positions.size(), 0);
  for (const Face& f : scene_.faces)
    for (uint32_t t = f.firstTriangle; t < f.firstTriangle + f.triangleCount; ++t)
      for (int k = 0; k < 3; ++k)
        if (!hasTexcoord_[scene_.triangles[t][k]]) unmapped[f.material] = 1;
  std::vector<std::string> names;
  bool textured = false;
  for (size_t m = 0; m < scene_.materials.size(); ++m) {
    Material& material = scene_.materials[m];
    if (!material.rhoTexture && !material.emissionTexture && !material.alphaTexture) continue;
    if (!unmapped[m]) {
      textured = true;
      continue;
    }
    names.push_back(quotedToken(material.name));
    if (material.rhoTexture) material.rho *= material.rhoTexture.texture->mean();
    if (material.alphaTexture) material.alpha *= material.alphaTexture.texture->meanAlpha();
    if (material.emissionTexture) material.emission *= material.emissionTexture.texture->mean();
    material.rhoTexture = {};
    material.emissionTexture = {};
    material.alphaTexture = {};
  }
  if (!textured) scene_.texcoords.clear();
  if (names.empty()) return;
  std::string list = names.front();
  for (size_t i = 1; i < names.size() && i < 5; ++i) list += ", " + names[i];
  if (names.size() > 5) list += fmt::format(" and {} more", names.size() - 5);
  scene_.warnings.push_back(fmt::format(
      "{} textured material{} ({}) on faces without texture coordinates: each takes its "
      "texture's mean",
      names.size(), names.size() == 1 ? "" : "s", list));
}

bool SceneBuilder::isDegenerate(const UVec3& t) const {
  const Vec3d a = scene_.positions[t.x], b = scene_.positions[t.y], c = scene_.positions[t.z];
  const double twiceArea = glm::length(glm::cross(b - a, c - a));
  const double longest = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
  // Zero area, or a sliver so thin that its normal is float noise.
  return !(twiceArea > 1e-6 * longest * longest);
}

void SceneBuilder::addFace(std::span<const uint32_t> corners, std::span<const UVec3> triangles,
                           uint32_t material, uint32_t object) {
  Face face;
  face.object = object;
  face.material = material;
  face.firstTriangle = uint32_t(scene_.triangles.size());
  for (const UVec3& t : triangles) {
    if (isDegenerate(t)) {
      ++degenerateTriangles_;
      continue;
    }
    scene_.triangles.push_back(t);
    scene_.triangleFace.push_back(uint32_t(scene_.faces.size()));
  }
  face.triangleCount = uint32_t(scene_.triangles.size()) - face.firstTriangle;
  if (face.triangleCount == 0) return;
  face.corners.assign(corners.begin(), corners.end());
  std::vector<Vec3> points;
  for (uint32_t c : corners) points.push_back(scene_.positions[c]);
  const Vec3d n = newellNormal(points);
  face.area = float(0.5 * glm::length(n));
  face.normal = Vec3(glm::normalize(n));
  scene_.faces.push_back(std::move(face));
}

void SceneBuilder::addPolygon(std::span<const uint32_t> corners, uint32_t material, uint32_t object,
                              const std::string& where) {
  if (corners.size() < 3)
    throw InputError(where,
                     fmt::format("a face needs at least 3 vertices, got {}", corners.size()));
  std::vector<Vec3> points;
  for (uint32_t c : corners) {
    if (c >= scene_.positions.size())
      throw InputError(where, fmt::format("vertex index {} out of range (the file has {} vertices)",
                                          c + 1, scene_.positions.size()));
    points.push_back(scene_.positions[c]);
  }
  const Vec3d normal = newellNormal(points);
  if (glm::length(normal) == 0.0) {
    degenerateTriangles_ += corners.size() - 2;
    return;
  }
  std::vector<UVec3> local = triangulatePolygon(points, normal);
  std::vector<UVec3> global;
  for (const UVec3& t : local) global.emplace_back(corners[t.x], corners[t.y], corners[t.z]);

  if (corners.size() == 3 || planeDeviation(points) <= kPlanarTolerance * polygonSize(points)) {
    addFace(corners, global, material, object);
    return;
  }
  for (const UVec3& t : global) {
    const std::array<uint32_t, 3> tri{t.x, t.y, t.z};
    addFace(tri, std::span<const UVec3>(&t, 1), material, object);
  }
}

std::optional<std::array<uint32_t, 4>> SceneBuilder::quadOf(const UVec3& a, const UVec3& b) const {
  // Exporters write a quad as two consecutive triangles sharing its diagonal: (p,q,r), (p,r,s).
  for (int rot = 0; rot < 3; ++rot) {
    const uint32_t p = a[rot], q = a[(rot + 1) % 3], r = a[(rot + 2) % 3];
    for (int k = 0; k < 3; ++k) {
      if (b[k] != p || b[(k + 1) % 3] != r) continue;
      const std::array<uint32_t, 4> quad{p, q, r, b[(k + 2) % 3]};
      std::array<Vec3, 4> pts;
      for (int j = 0; j < 4; ++j) pts[j] = scene_.positions[quad[j]];
      const Vec3d n = newellNormal(pts);
      if (glm::length(n) == 0.0 || planeDeviation(pts) > kPlanarTolerance * polygonSize(pts))
        return std::nullopt;
      for (int j = 0; j < 4; ++j) {
        const Vec3d e0 = Vec3d(pts[(j + 1) % 4]) - Vec3d(pts[j]);
        const Vec3d e1 = Vec3d(pts[(j + 2) % 4]) - Vec3d(pts[(j + 1) % 4]);
        if (glm::dot(glm::cross(e0, e1), n) <= 0.0) return std::nullopt;  // not convex
      }
      return quad;
    }
  }
  return std::nullopt;
}

void SceneBuilder::addTriangleMesh(std::span<const uint32_t> indices, uint32_t material,
                                   uint32_t object, const std::string& where) {
  if (indices.size() % 3 != 0)
    throw InputError(where,
                     fmt::format("triangle index count {} is not a multiple of 3", indices.size()));
  for (uint32_t i : indices)
    if (i >= scene_.positions.size())
      throw InputError(where, fmt::format("vertex index {} out of range ({} vertices)", i,
                                          scene_.positions.size()));
  const size_t count = indices.size() / 3;
  auto tri = [&](size_t t) {
    return UVec3(indices[3 * t], indices[3 * t + 1], indices[3 * t + 2]);
  };
  for (size_t t = 0; t < count; ++t) {
    const UVec3 a = tri(t);
    if (t + 1 < count) {
      const UVec3 b = tri(t + 1);
      if (auto quad = quadOf(a, b)) {
        const std::array<UVec3, 2> pair{a, b};
        addFace(*quad, pair, material, object);
        ++t;
        continue;
      }
    }
    const std::array<uint32_t, 3> corners{a.x, a.y, a.z};
    addFace(corners, std::span<const UVec3>(&a, 1), material, object);
  }
}

void SceneBuilder::warn(const std::string& file, const std::string& text) {
  scene_.warnings.push_back(file == scene_.name ? text : file + ": " + text);
}

Scene SceneBuilder::build() {
  if (degenerateTriangles_ > 0)
    scene_.warnings.push_back(
        fmt::format("dropped {} degenerate triangle{} (zero or near-zero area)",
                    degenerateTriangles_, degenerateTriangles_ == 1 ? "" : "s"));
  degenerateTriangles_ = 0;
  if (clampedMaterials_ > 0)
    scene_.warnings.push_back(fmt::format(
        "{} material{} of reflectance 1 taken as {} (rho must be below 1: light would never "
        "fade in a closed room)",
        clampedMaterials_, clampedMaterials_ == 1 ? "" : "s", kMaxReflectance));
  clampedMaterials_ = 0;
  if (!scene_.camera && !scene_.cameras.empty()) scene_.camera = scene_.cameras.front().second;
  resolveUnmappedTextures();
  if (!scene_.texcoords.empty()) scene_.texcoords.resize(scene_.positions.size(), Vec2(0.0f));
  if (!scene_.vertexAlpha.empty()) scene_.vertexAlpha.resize(scene_.positions.size(), 1.0f);
  return std::move(scene_);
}

}  // namespace rad
