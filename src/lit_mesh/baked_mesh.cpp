#include <fmt/format.h>
#include <radiosity/baked_mesh.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <span>
#include <stdexcept>
#include <unordered_map>

#include "lit_mesh/lit_mesh_texturing.h"

namespace rad {

namespace {

// One scene triangle cut until no edge exceeds the limit: by longest-edge bisection, which keeps
// the pieces well shaped, down to slivers (no taller than half the limit over their longest
// edge), which become a strip: a zipper between the longest edge and the path over the third
// corner, both cut into steps of half the limit. The pieces thus follow the triangle's area and
// the length of its edges (a long sliver is a row of pieces, not a grid of n^2). Bisection
// midpoints are shared between the pieces that split the same edge.
struct TrianglePieces {
  std::vector<Vec3> positions;
  std::vector<uint32_t> indices;  // CCW like the scene triangle
};

class TriangleCut {
 public:
  TriangleCut(float maxEdge, TrianglePieces& out) : limit_(maxEdge), out_(out) {}

  void cut(uint32_t a, uint32_t b, uint32_t c, int depth) {
    // (p, q) the longest edge and r the third corner, in the winding of (a, b, c).
    const std::array<uint32_t, 3> v{a, b, c};
    int longest = 0;
    float most = 0.0f;
    for (int k = 0; k < 3; ++k) {
      const float len = length(v[size_t(k)], v[size_t((k + 1) % 3)]);
      if (len > most) most = len, longest = k;
    }
    if (!(most > limit_) || depth == kMaxDepth) {
      out_.indices.insert(out_.indices.end(), {a, b, c});
      return;
    }
    const uint32_t p = v[size_t(longest)], q = v[size_t((longest + 1) % 3)];
    const uint32_t r = v[size_t((longest + 2) % 3)];
    const Vec3 normal = glm::cross(at(q) - at(p), at(r) - at(p));
    if (glm::length(normal) / most <= 0.5f * limit_) return strip(p, q, r);
    const uint32_t m = midpoint(p, q);
    cut(p, m, r, depth + 1);
    cut(m, q, r, depth + 1);
  }

 private:
  // The pieces halve at every level: the bound only guards against NaN input.
  static constexpr int kMaxDepth = 64;

  const Vec3& at(uint32_t i) const { return out_.positions[i]; }
  float length(uint32_t i, uint32_t j) const { return glm::length(at(j) - at(i)); }
  uint32_t midpoint(uint32_t i, uint32_t j) {
    const uint64_t key = uint64_t(std::min(i, j)) << 32 | std::max(i, j);
    const auto [it, added] = midpoints_.try_emplace(key, uint32_t(out_.positions.size()));
    if (added) out_.positions.push_back(0.5f * (at(i) + at(j)));
    return it->second;
  }
  // Appends the points strictly between i and j, steps of at most half the limit.
  void appendSteps(uint32_t i, uint32_t j, std::vector<uint32_t>& chain) {
    const int steps = int(std::ceil(length(i, j) / (0.5f * limit_)));
    const Vec3 from = at(i), to = at(j);
    for (int k = 1; k < steps; ++k) {
      chain.push_back(uint32_t(out_.positions.size()));
      out_.positions.push_back(from + (to - from) * (float(k) / float(steps)));
    }
  }
  void strip(uint32_t p, uint32_t q, uint32_t r) {
    // Both chains run from p to q; the third corner projects inside the longest edge, so both
    // advance monotonically along it and a merge by that coordinate joins neighbours only.
    std::vector<uint32_t> bottom{p}, top{p};
    appendSteps(p, q, bottom);
    bottom.push_back(q);
    appendSteps(p, r, top);
    top.push_back(r);
    appendSteps(r, q, top);
    top.push_back(q);
    const Vec3 origin = at(p), axis = at(q) - at(p);
    auto along = [&](uint32_t i) { return glm::dot(at(i) - origin, axis); };
    auto emit = [&](uint32_t x, uint32_t y, uint32_t z) {
      if (x != y && y != z && z != x) out_.indices.insert(out_.indices.end(), {x, y, z});
    };
    size_t i = 0, j = 0;
    while (i + 1 < bottom.size() || j + 1 < top.size()) {
      if (j + 1 == top.size() ||
          (i + 1 < bottom.size() && along(bottom[i + 1]) <= along(top[j + 1]))) {
        emit(bottom[i], bottom[i + 1], top[j]);
        ++i;
      } else {
        emit(bottom[i], top[j + 1], top[j]);
        ++j;
      }
    }
  }

  float limit_;
  TrianglePieces& out_;
  std::unordered_map<uint64_t, uint32_t> midpoints_;
};

TrianglePieces cutTriangle(const Scene& scene, uint32_t triangle, float maxEdge) {
  TrianglePieces pieces;
  const UVec3& t = scene.triangles[triangle];
  pieces.positions = {scene.positions[t.x], scene.positions[t.y], scene.positions[t.z]};
  TriangleCut(maxEdge, pieces).cut(0, 1, 2, 0);
  return pieces;
}

// The scene's triangles in object order; `groups` gets each object's range of them.
std::vector<uint32_t> trianglesByObject(const Scene& scene, std::vector<LitMeshGroup>& groups) {
  std::vector<std::vector<uint32_t>> facesOf(scene.objects.size());
  for (uint32_t f = 0; f < scene.faces.size(); ++f) facesOf[scene.faces[f].object].push_back(f);
  std::vector<uint32_t> order;
  for (uint32_t o = 0; o < scene.objects.size(); ++o) {
    const uint32_t first = uint32_t(order.size());
    for (const uint32_t f : facesOf[o])
      for (uint32_t t = 0; t < scene.faces[f].triangleCount; ++t)
        order.push_back(scene.faces[f].firstTriangle + t);
    groups.push_back({scene.objects[o].name, first, uint32_t(order.size()) - first});
  }
  return order;
}

// An estimate of the pieces from above (bisection's cover at least maxEdge^2 / 16 each, a
// strip's about a quarter of maxEdge of the triangle's edges each; a two-sided triangle's twice),
// checked before any is made.
void checkPieceCount(const Scene& scene, std::span<const uint32_t> triangles, float maxEdge) {
  double estimate = 0.0;
  for (const uint32_t t : triangles) {
    const UVec3& tri = scene.triangles[t];
    const Vec3 a = scene.positions[tri.x], b = scene.positions[tri.y], c = scene.positions[tri.z];
    const double perimeter = glm::length(b - a) + glm::length(c - b) + glm::length(a - c);
    const double sides = scene.materialOf(t).twoSided ? 2.0 : 1.0;
    estimate += sides * (16.0 * scene.triangleArea(t) / (maxEdge * maxEdge) +
                         8.0 * perimeter / maxEdge + 1.0);
  }
  if (estimate > kMaxBakedTriangles)
    throw std::invalid_argument(
        fmt::format("bake: cutting the scene to {} would make about {:.3g} triangles (at most "
                    "{:.3g}); use larger voxels",
                    maxEdge, estimate, kMaxBakedTriangles));
}

}  // namespace

SurfaceBake cutSurfaces(const Scene& scene, float maxEdge, bool withTextures) {
  if (!(maxEdge > 0.0f)) throw std::invalid_argument("bake: the longest edge must be positive");
  SurfaceBake bake;
  LitMesh& out = bake.mesh;
  const std::vector<uint32_t> order = trianglesByObject(scene, out.groups);
  checkPieceCount(scene, order, maxEdge);
  std::vector<TrianglePieces> pieces(order.size());
  tbb::parallel_for(size_t(0), order.size(),
                    [&](size_t i) { pieces[i] = cutTriangle(scene, order[i], maxEdge); });
  // Where each triangle's vertices and pieces go (a two-sided one's twice: its back side has
  // light of its own); the groups then count pieces.
  std::vector<uint64_t> vertexStart(order.size() + 1, 0), pieceStart(order.size() + 1, 0);
  for (size_t i = 0; i < order.size(); ++i) {
    const uint64_t sides = scene.materialOf(order[i]).twoSided ? 2 : 1;
    vertexStart[i + 1] = vertexStart[i] + sides * pieces[i].positions.size();
    pieceStart[i + 1] = pieceStart[i] + sides * pieces[i].indices.size() / 3;
  }
  if (vertexStart.back() > UINT32_MAX)
    throw std::invalid_argument("bake: more than 2^32 vertices; use a longer edge");
  for (LitMeshGroup& g : out.groups) {
    const uint64_t begin = pieceStart[g.firstTriangle];
    g.triangleCount = uint32_t(pieceStart[g.firstTriangle + g.triangleCount] - begin);
    g.firstTriangle = uint32_t(begin);
  }
  out.positions.resize(vertexStart.back());
  out.normals.resize(vertexStart.back());
  out.colors.resize(vertexStart.back());
  bake.at.resize(vertexStart.back());
  out.indices.resize(3 * pieceStart.back());
  // The textures made before the parallel cut, which only reads them.
  LitMeshTexturing texturing(scene, out);
  const bool textures = withTextures && texturing.any();
  if (textures) {
    for (uint32_t m = 0; m < scene.materials.size(); ++m)
      if (texturing.textured(m)) texturing.textureOf(m);
    out.texcoords.resize(out.positions.size());
    out.triangleTextures.resize(out.indices.size() / 3, LitMesh::kUntextured);
    bake.underTexture.resize(out.positions.size(), 0);
  }
  tbb::parallel_for(size_t(0), order.size(), [&](size_t i) {
    const uint32_t triangle = order[i];
    const Vec3 normal = scene.triangleNormal(triangle);
    TrianglePieces& p = pieces[i];
    uint32_t* index = out.indices.data() + 3 * pieceStart[i];
    const int sides = scene.materialOf(triangle).twoSided ? 2 : 1;
    for (int side = 0; side < sides; ++side) {
      const bool front = side == 0;
      const uint32_t base = uint32_t(vertexStart[i] + size_t(side) * p.positions.size());
      const uint32_t material = scene.faceOf(triangle).material;
      const bool textured = textures && texturing.textured(material);
      for (size_t v = 0; v < p.positions.size(); ++v) {
        out.positions[base + v] = p.positions[v];
        out.normals[base + v] = front ? normal : -normal;
        bake.at[base + v] = {p.positions[v], normal, triangle, front,
                             scene.barycentricOf(triangle, p.positions[v])};
        if (!textured) continue;
        out.texcoords[base + v] = texturing.texcoordAt(triangle, bake.at[base + v].barycentric);
        bake.underTexture[base + v] = 1;
      }
      if (textured) {
        const uint64_t first = pieceStart[i] + uint64_t(side) * (p.indices.size() / 3);
        std::fill_n(out.triangleTextures.begin() + long(first), p.indices.size() / 3,
                    texturing.textureOf(material));
      }
      // The back side is wound the other way round, so that it faces out of its own side.
      for (size_t k = 0; k < p.indices.size(); k += 3) {
        *index++ = base + p.indices[k];
        *index++ = base + p.indices[k + (front ? 1 : 2)];
        *index++ = base + p.indices[k + (front ? 2 : 1)];
      }
    }
    p = {};
  });
  return bake;
}

void shadeSurfaces(SurfaceBake& bake, const SurfaceRadiance& radiance) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, bake.at.size(), 1024), [&](const auto& r) {
    for (size_t v = r.begin(); v != r.end(); ++v)
      bake.mesh.colors[v] = radiance.radiance(bake.at[v]);
  });
}

LitMesh bakeSurfaceRadiance(const Scene& scene, const SurfaceRadiance& radiance, float maxEdge) {
  SurfaceBake bake = cutSurfaces(scene, maxEdge);
  shadeSurfaces(bake, radiance);
  return std::move(bake.mesh);
}

LitMesh bakeSurfaceLight(const Scene& scene, const SurfaceSolution& solution, float maxEdge) {
  SurfaceBake bake = cutSurfaces(scene, maxEdge, true);
  shadeSurfaces(bake, solution);
  // Under a texture, the light a white surface would send: the texture is the albedo.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, bake.underTexture.size(), 1024),
                    [&](const auto& r) {
                      for (size_t v = r.begin(); v != r.end(); ++v)
                        if (bake.underTexture[v])
                          bake.mesh.colors[v] = solution.irradiance(bake.at[v]) / glm::pi<float>();
                    });
  return std::move(bake.mesh);
}

}  // namespace rad
