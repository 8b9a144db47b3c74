// Quadtree patch meshing. Quads are split by their bilinear map (the children of a planar quad
// are the bilinear map restricted to the four quadrants of its parameter square), triangles by
// their edge midpoints (Loop-style 1-to-4 split); point location descends the tree by the
// parameter (u, v) or the barycentrics of the point. Inverse bilinear map: I. Quilez, "Inverse
// bilinear interpolation" (2010).
#include "patch/patch_mesh.h"

#include <fmt/format.h>
#include <radiosity/error.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_set>

#include "geometry/sampling.h"
#include "patch/patch_quadrature.h"

namespace rad {

namespace {

constexpr int kMaxDepth = kMaxPatchDepth;
constexpr float kCreaseCos = 0.8f;  // about 37 degrees: a box's walls stay apart, a sphere smooth

// The corners (indices into Scene::positions) of each quadtree root of a face: the face itself
// when it is a convex quad, else each of its triangles.
std::vector<std::vector<uint32_t>> rootCorners(const Scene& scene, const Face& face) {
  std::vector<std::vector<uint32_t>> roots;
  if (face.corners.size() == 4 && face.triangleCount == 2) {
    bool convex = true;
    for (int k = 0; k < 4; ++k) {
      const Vec3& a = scene.positions[face.corners[k]];
      const Vec3& b = scene.positions[face.corners[(k + 1) % 4]];
      const Vec3& c = scene.positions[face.corners[(k + 2) % 4]];
      convex = convex && glm::dot(glm::cross(b - a, c - b), face.normal) > 0.0f;
    }
    if (convex) return {face.corners};
  }
  for (uint32_t t = face.firstTriangle; t < face.firstTriangle + face.triangleCount; ++t)
    roots.push_back({scene.triangles[t].x, scene.triangles[t].y, scene.triangles[t].z});
  return roots;
}

float longestEdge(const Scene& scene, const std::vector<uint32_t>& corners) {
  float longest = 0.0f;
  for (size_t k = 0; k < corners.size(); ++k)
    longest = std::max(longest, glm::distance(scene.positions[corners[k]],
                                              scene.positions[corners[(k + 1) % corners.size()]]));
  return longest;
}

int depthFor(float edge, float patchSize) {
  if (edge <= patchSize) return 0;
  return std::min(kMaxDepth, int(std::ceil(std::log2(double(edge) / double(patchSize)) - 1e-9)));
}

float cross2(Vec2 a, Vec2 b) {
  return a.x * b.y - a.y * b.x;
}

// (u, v) with p = bilinear(c0, c1, c2, c3; u, v), in 2D coordinates of the quad's plane.
Vec2 inverseBilinear(Vec2 p, Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const Vec2 e = b - a, f = d - a, g = a - b + c - d, h = p - a;
  const float k2 = cross2(g, f), k1 = cross2(e, f) + cross2(h, g), k0 = cross2(h, e);
  auto uFor = [&](float v) {
    const Vec2 den = e + g * v;
    return std::abs(den.x) > std::abs(den.y) ? (h.x - f.x * v) / den.x : (h.y - f.y * v) / den.y;
  };
  float v;
  if (std::abs(k2) < 1e-6f * std::abs(k1)) {
    v = -k0 / k1;
  } else {
    const float w = std::sqrt(std::max(0.0f, k1 * k1 - 4.0f * k0 * k2));
    v = (-k1 - w) / (2.0f * k2);
    const float u = uFor(v);
    if (v < -0.01f || v > 1.01f || u < -0.01f || u > 1.01f) v = (-k1 + w) / (2.0f * k2);
  }
  return glm::clamp(Vec2(uFor(v), v), Vec2(0.0f), Vec2(1.0f));
}

}  // namespace

namespace {

// Each root's longest edge and its sides (2 for a two-sided face): what the patch count of a
// patch size follows from.
std::vector<std::pair<float, int>> rootEdges(const Scene& scene) {
  std::vector<std::pair<float, int>> roots;
  for (const Face& face : scene.faces) {
    const int sides = scene.materials[face.material].twoSided ? 2 : 1;
    for (const auto& corners : rootCorners(scene, face))
      roots.push_back({longestEdge(scene, corners), sides});
  }
  return roots;
}

double patchCount(const std::vector<std::pair<float, int>>& roots, float size) {
  double n = 0.0;
  for (const auto& [edge, sides] : roots) n += double(sides) * std::pow(4.0, depthFor(edge, size));
  return n;
}

}  // namespace

double PatchMesh::patchCountFor(const Scene& scene, float patchSize) {
  return patchCount(rootEdges(scene), patchSize);
}

float PatchMesh::patchSizeFor(const Scene& scene, size_t target) {
  const std::vector<std::pair<float, int>> roots = rootEdges(scene);
  // Every face root is a patch at least: `target` counts the patches beyond those, so that a
  // scene of many small faces still has its large ones split (a real atrium's 36,711 faces
  // against a target of 4,000 left its 83 m floor one patch, whose form factors then ran far
  // past 1). The largest size that gives that many (the count falls as the size grows).
  const double wanted = patchCount(roots, std::numeric_limits<float>::infinity()) + double(target);
  double lo = std::log(std::max(scene.bounds().diagonal(), 1e-30f) * 1e-5), hi = lo + std::log(2e5);
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (patchCount(roots, float(std::exp(mid))) >= wanted ? lo : hi) = mid;
  }
  return float(std::exp(lo));
}

PatchMesh::PatchMesh(const Scene& scene, const PatchMeshSettings& settings) : scene_(&scene) {
  if (!(settings.patchSize >= 0.0f) || !std::isfinite(settings.patchSize))
    throw InputError("patch settings",
                     fmt::format("patch size {} must be positive", settings.patchSize));
  if (settings.patchSize == 0.0f && settings.targetPatches < 1)
    throw InputError("patch settings", "patch count must be at least 1");
  patchSize_ =
      settings.patchSize > 0.0f ? settings.patchSize : patchSizeFor(scene, settings.targetPatches);
  weldCell_ = std::max(scene.bounds().diagonal(), 1e-30f) * 1e-6f;
  triangleRoot_.assign(2 * scene.triangles.size(), kNoNode);
  for (uint32_t f = 0; f < scene.faces.size(); ++f) {
    const Face& face = scene.faces[f];
    for (auto corners : rootCorners(scene, face)) {
      addRoot(f, false, corners);
      if (!scene.materials[face.material].twoSided) continue;
      std::reverse(corners.begin(), corners.end());
      addRoot(f, true, corners);
    }
  }
}

void PatchMesh::addRoot(uint32_t face, bool back, std::span<const uint32_t> corners) {
  const Face& f = scene_->faces[face];
  const Vec3 normal = back ? -f.normal : f.normal;
  PatchNode node;
  node.quad = corners.size() == 4;
  node.root = uint32_t(roots_.size());
  for (size_t k = 0; k < corners.size(); ++k)
    node.corners[k] = weldedVertex(scene_->positions[corners[k]], normal);
  roots_.push_back({face, uint32_t(nodes_.size()), back, 0, 0, 0});
  nodes_.push_back(node);
  // A quad root serves both triangles of its face; a triangle root the one it was made from.
  for (uint32_t t = f.firstTriangle; t < f.firstTriangle + f.triangleCount; ++t) {
    const UVec3& tri = scene_->triangles[t];
    const bool mine =
        node.quad || (std::find(corners.begin(), corners.end(), tri.x) != corners.end() &&
                      std::find(corners.begin(), corners.end(), tri.y) != corners.end() &&
                      std::find(corners.begin(), corners.end(), tri.z) != corners.end());
    if (!mine) continue;
    triangleRoot_[2 * t + (back ? 1 : 0)] = roots_.back().node;
    if (roots_.back().triangleCount++ == 0) roots_.back().firstTriangle = t;
  }
  float edge = 0.0f;
  for (size_t k = 0; k < corners.size(); ++k)
    edge = std::max(edge, glm::distance(scene_->positions[corners[k]],
                                        scene_->positions[corners[(k + 1) % corners.size()]]));
  const int depth = depthFor(edge, patchSize_);
  roots_.back().baseDepth = uint8_t(depth);
  subdivide(roots_.back().node, depth, normal);
}

// Every split adds leaves, so a mesh with more patches than the leaves wanted has split a patch
// that none of them lies below: the addresses are not a refinement of this mesh.
bool PatchMesh::refineToLeaves(std::span<const uint64_t> addresses) {
  const std::unordered_set<uint64_t> wanted(addresses.begin(), addresses.end());
  if (wanted.size() != addresses.size()) return false;
  std::vector<uint32_t> split;
  while (size() <= wanted.size()) {
    split.clear();
    for (uint32_t p = 0; p < size(); ++p)
      if (!wanted.contains(nodeAddress(patches_[p].node))) split.push_back(p);
    if (split.empty()) return size() == wanted.size();
    const size_t before = size();
    refine(split);
    if (size() == before) return false;
  }
  return false;
}

void PatchMesh::refine(std::span<const uint32_t> patches) {
  bool split = false;
  for (uint32_t p : patches) {
    const uint32_t node = patches_[p].node;
    if (nodes_[node].depth >= kMaxDepth || !nodes_[node].leaf()) continue;
    subdivide(node, 1, patches_[p].normal);
    split = true;
  }
  if (!split) return;
  refined_ = true;
  numberPatches();
}

// The leaves in depth-first order from each root: the order the constructor gives them.
void PatchMesh::numberPatches() {
  patches_.clear();
  std::vector<uint32_t> stack;
  for (const PatchRoot& root : roots_) {
    stack.push_back(root.node);
    while (!stack.empty()) {
      const uint32_t n = stack.back();
      stack.pop_back();
      if (nodes_[n].leaf()) {
        finishPatch(n);
        continue;
      }
      nodes_[n].patch = kNoPatch;
      for (uint32_t k = 4; k-- > 0;) stack.push_back(nodes_[n].firstChild + k);
    }
  }
}

std::vector<HangingVertex> PatchMesh::hangingVertices() const {
  std::vector<HangingVertex> out;
  if (!refined_) return out;
  std::vector<uint32_t> byDepth(patches_.size());
  for (uint32_t p = 0; p < byDepth.size(); ++p) byDepth[p] = p;
  std::stable_sort(byDepth.begin(), byDepth.end(),
                   [&](uint32_t a, uint32_t b) { return nodeOf(a).depth < nodeOf(b).depth; });
  // A refined neighbour puts its corners at the dyadic points of this leaf's edge. Each leaf's
  // are found apart (in parallel: a relighter asks at every change of the quadtree), then
  // listed in depth order.
  auto edge = [&](auto&& self, std::vector<HangingVertex>& found, uint32_t a, uint32_t b,
                  const Vec3& normal, int levels) -> void {
    if (levels == 0) return;
    const uint32_t m = findVertex(0.5f * (vertices_[a] + vertices_[b]), normal);
    if (m == kNoNode) return;
    found.push_back({m, a, b});
    self(self, found, a, m, normal, levels - 1);
    self(self, found, m, b, normal, levels - 1);
  };
  std::vector<std::vector<HangingVertex>> ofLeaf(byDepth.size());
  tbb::parallel_for(size_t(0), byDepth.size(), [&](size_t k) {
    const uint32_t p = byDepth[k];
    const PatchNode& node = nodeOf(p);
    const int levels = kMaxDepth - node.depth;
    for (int c = 0; c < node.cornerCount(); ++c)
      edge(edge, ofLeaf[k], node.corners[c], node.corners[(c + 1) % node.cornerCount()],
           patches_[p].normal, levels);
  });
  for (const std::vector<HangingVertex>& found : ofLeaf)
    out.insert(out.end(), found.begin(), found.end());
  return out;
}

void PatchMesh::subdivide(uint32_t index, int depth, const Vec3& normal) {
  if (depth == 0) return finishPatch(index);
  const PatchNode parent = nodes_[index];
  auto mid = [&](uint32_t a, uint32_t b) {
    return weldedVertex(0.5f * (vertices_[a] + vertices_[b]), normal);
  };
  const auto& c = parent.corners;
  std::array<std::array<uint32_t, 4>, 4> kids;
  if (parent.quad) {
    const uint32_t e01 = mid(c[0], c[1]), e12 = mid(c[1], c[2]), e23 = mid(c[2], c[3]),
                   e30 = mid(c[3], c[0]);
    const uint32_t m = weldedVertex(
        0.25f * (vertices_[c[0]] + vertices_[c[1]] + vertices_[c[2]] + vertices_[c[3]]), normal);
    kids = {{{c[0], e01, m, e30}, {e01, c[1], e12, m}, {m, e12, c[2], e23}, {e30, m, e23, c[3]}}};
  } else {
    const uint32_t m01 = mid(c[0], c[1]), m12 = mid(c[1], c[2]), m20 = mid(c[2], c[0]);
    kids = {{{c[0], m01, m20, 0}, {m01, c[1], m12, 0}, {m20, m12, c[2], 0}, {m12, m20, m01, 0}}};
  }
  const uint32_t first = uint32_t(nodes_.size());
  nodes_[index].firstChild = first;
  for (int k = 0; k < 4; ++k) {
    PatchNode child;
    child.corners = kids[k];
    child.parent = index;
    child.root = parent.root;
    child.depth = uint8_t(parent.depth + 1);
    child.path = (parent.path << 2) | uint32_t(k);
    child.quad = parent.quad;
    nodes_.push_back(child);
  }
  for (uint32_t k = 0; k < 4; ++k) subdivide(first + k, depth - 1, normal);
}

void PatchMesh::finishPatch(uint32_t index) {
  PatchNode& node = nodes_[index];
  const PatchRoot& root = roots_[node.root];
  const Face& face = scene_->faces[root.face];
  Patch p;
  p.node = index;
  p.face = root.face;
  p.object = face.object;
  p.material = face.material;
  p.normal = root.back ? -face.normal : face.normal;
  const Vec3 a = vertices_[node.corners[0]], b = vertices_[node.corners[1]],
             c = vertices_[node.corners[2]];
  const float a1 = 0.5f * glm::length(glm::cross(b - a, c - a));
  p.area = a1;
  Vec3 weighted = a1 * (a + b + c) / 3.0f;
  if (node.quad) {
    const Vec3 d = vertices_[node.corners[3]];
    const float a2 = 0.5f * glm::length(glm::cross(c - a, d - a));
    p.area += a2;
    weighted += a2 * (a + c + d) / 3.0f;
  }
  p.centroid = p.area > 0.0f ? weighted / p.area : a;
  p.rho = scene_->materials[p.material].rho;
  node.patch = uint32_t(patches_.size());
  patches_.push_back(p);
  const Material& m = scene_->materials[p.material];
  if (m.rhoTexture || m.emissionTexture || !m.opaque()) applyMaterialMeans(node.patch);
}

// A textured patch's reflectance and emission are the textures' means over it (area-weighted,
// linear): the midpoint rule's 4 x 4 points, each the texture averaged over a quarter of the
// patch's size, so that a patch of any size sees all of its texels. Where the material is not
// opaque the means are weighted by the coverage, and its mean is the patch's; a coverage that
// varies over the patch (a Mask's cut-out, thresholded texel by texel) is taken at 16 x 16 points.
void PatchMesh::applyMaterialMeans(uint32_t index) {
  Patch& p = patches_[index];
  const Material& m = scene_->materials[p.material];
  const int points = uniformCoverage(index) ? 16 : 256;
  const float footprint = 0.25f * std::sqrt(p.area) * 4.0f / std::sqrt(float(points));
  const PatchRoot& root = roots_[nodes_[p.node].root];
  Color rho(0.0f), emission(0.0f), plainRho(0.0f), plainEmission(0.0f);
  double covered = 0.0;
  for (const QuadraturePoint& q : midpointRule(*this, index, points)) {
    uint32_t triangle = 0;
    const Vec2 b =
        scene_->locateOnTriangles(root.firstTriangle, root.triangleCount, q.position, triangle);
    const Color r = scene_->textureAt(m.rhoTexture, triangle, b, footprint);
    const Color e = scene_->textureAt(m.emissionTexture, triangle, b, footprint);
    const float c = scene_->coverageAt(triangle, b, footprint);
    rho += float(q.weight) * c * r;
    emission += float(q.weight) * c * e;
    plainRho += float(q.weight) * r;
    plainEmission += float(q.weight) * e;
    covered += q.weight * c;
  }
  if (m.opaque()) {
    p.rho = m.rho * rho;
    p.emissionTint = emission;
    return;
  }
  // A patch cut away whole shows the plain means (no light ever reaches it).
  p.coverage = float(covered);
  p.rho = m.rho * (covered > 0.0 ? rho / float(covered) : plainRho);
  p.emissionTint = covered > 0.0 ? emission / float(covered) : plainEmission;
}

float PatchMesh::coverageAt(uint32_t patch, const Vec3& point) const {
  const PatchRoot& root = roots_[nodes_[patches_[patch].node].root];
  uint32_t triangle = 0;
  const Vec2 b = scene_->locateOnTriangles(root.firstTriangle, root.triangleCount, point, triangle);
  return scene_->coverageAt(triangle, b);
}

bool PatchMesh::uniformCoverage(uint32_t patch) const {
  const PatchRoot& root = roots_[nodes_[patches_[patch].node].root];
  for (uint32_t t = root.firstTriangle; t < root.firstTriangle + root.triangleCount; ++t)
    if (!scene_->uniformCoverage(t)) return false;
  return true;
}

uint64_t PatchMesh::weldKey(const Vec3& p, float cell) {
  auto at = [&](int k) { return uint64_t(std::llround(double(p[k]) / double(cell))); };
  return (at(0) * 73856093u) ^ (at(1) * 19349663u) ^ (at(2) * 83492791u);
}

uint32_t PatchMesh::findVertex(const Vec3& p, const Vec3& normal) const {
  const auto it = weld_.find(weldKey(p, weldCell_));
  if (it == weld_.end()) return kNoNode;
  for (uint32_t v : it->second)
    if (glm::distance(vertices_[v], p) <= weldCell_ &&
        glm::dot(vertexNormals_[v], normal) > kCreaseCos)
      return v;
  return kNoNode;
}

uint32_t PatchMesh::weldedVertex(const Vec3& p, const Vec3& normal) {
  std::vector<uint32_t>& bucket = weld_[weldKey(p, weldCell_)];
  for (uint32_t v : bucket)
    if (glm::distance(vertices_[v], p) <= weldCell_ &&
        glm::dot(vertexNormals_[v], normal) > kCreaseCos)
      return v;
  bucket.push_back(uint32_t(vertices_.size()));
  vertices_.push_back(p);
  vertexNormals_.push_back(normal);
  return bucket.back();
}

int PatchMesh::corners(uint32_t patch, std::array<Vec3, 4>& out) const {
  const PatchNode& node = nodeOf(patch);
  for (int k = 0; k < node.cornerCount(); ++k) out[k] = vertices_[node.corners[k]];
  return node.cornerCount();
}

namespace {

// One step down a quad's quadtree: the child holding parameter point uv, and uv in it.
int quadChild(Vec2& uv) {
  const int bu = uv.x >= 0.5f ? 1 : 0, bv = uv.y >= 0.5f ? 1 : 0;
  static constexpr int kChild[2][2] = {{0, 3}, {1, 2}};  // [bu][bv], the children's order
  uv = glm::clamp(2.0f * uv - Vec2(float(bu), float(bv)), Vec2(0.0f), Vec2(1.0f));
  return kChild[bu][bv];
}

// One step down a triangle's quadtree: the child holding barycentric point w, and w in it.
int triangleChild(Vec3& w) {
  const int k = w.x >= 0.5f ? 0 : w.y >= 0.5f ? 1 : w.z >= 0.5f ? 2 : 3;
  if (k < 3) {
    w *= 2.0f;
    w[k] -= 1.0f;
  } else {
    w = Vec3(1.0f) - 2.0f * w;  // the middle child's corners are the opposite midpoints
  }
  w = glm::max(w, Vec3(0.0f));
  w /= std::max(w.x + w.y + w.z, 1e-30f);
  return k;
}

}  // namespace

// The point's coordinates in a root: (u, v) of the quad's bilinear map, or barycentrics.
PatchMesh::RootPoint PatchMesh::rootPoint(uint32_t root, const Vec3& point) const {
  const PatchNode& node = nodes_[root];
  RootPoint r;
  if (node.quad) {
    const Vec3 n = roots_[node.root].back ? -scene_->faces[roots_[node.root].face].normal
                                          : scene_->faces[roots_[node.root].face].normal;
    Vec3 t, b;
    orthonormalBasis(n, t, b);
    auto flat = [&](uint32_t v) {
      return Vec2(glm::dot(vertices_[v], t), glm::dot(vertices_[v], b));
    };
    r.uv = inverseBilinear(Vec2(glm::dot(point, t), glm::dot(point, b)), flat(node.corners[0]),
                           flat(node.corners[1]), flat(node.corners[2]), flat(node.corners[3]));
    return r;
  }
  const Vec3 a = vertices_[node.corners[0]], e1 = vertices_[node.corners[1]] - a,
             e2 = vertices_[node.corners[2]] - a, d = point - a;
  const float d00 = glm::dot(e1, e1), d01 = glm::dot(e1, e2), d11 = glm::dot(e2, e2);
  const float d20 = glm::dot(d, e1), d21 = glm::dot(d, e2);
  const float den = d00 * d11 - d01 * d01;
  Vec3 w(0.0f, (d11 * d20 - d01 * d21) / den, (d00 * d21 - d01 * d20) / den);
  w = glm::max(Vec3(1.0f - w.y - w.z, w.y, w.z), Vec3(0.0f));
  r.w = w / std::max(w.x + w.y + w.z, 1e-30f);
  return r;
}

PatchMesh::Location PatchMesh::locate(uint32_t triangle, bool frontFace, const Vec3& point) const {
  Location loc;
  const uint32_t index = triangleRoot_[2 * size_t(triangle) + (frontFace ? 0 : 1)];
  if (index == kNoNode) return loc;
  const PatchNode* node = &nodes_[index];
  RootPoint r = rootPoint(index, point);
  while (!node->leaf())
    node = &nodes_[node->firstChild + uint32_t(node->quad ? quadChild(r.uv) : triangleChild(r.w))];
  if (node->quad)
    loc.weights = {(1 - r.uv.x) * (1 - r.uv.y), r.uv.x * (1 - r.uv.y), r.uv.x * r.uv.y,
                   (1 - r.uv.x) * r.uv.y};
  else
    loc.weights = {r.w.x, r.w.y, r.w.z, 0.0f};
  loc.patch = node->patch;
  return loc;
}

int PatchMesh::finestDepth(uint32_t root, int levels) const {
  return std::min(kMaxDepth, int(roots_[root].baseDepth) + levels);
}

uint64_t PatchMesh::finestKey(uint32_t triangle, bool frontFace, const Vec3& point,
                              int levels) const {
  const uint32_t index = triangleRoot_[2 * size_t(triangle) + (frontFace ? 0 : 1)];
  if (index == kNoNode) return kNoKey;
  const PatchNode& root = nodes_[index];
  RootPoint r = rootPoint(index, point);
  uint64_t path = 0;
  for (int d = finestDepth(root.root, levels); d > 0; --d)
    path = (path << 2) | uint64_t(root.quad ? quadChild(r.uv) : triangleChild(r.w));
  return (uint64_t(root.root) << 32) | path;
}

std::pair<uint64_t, uint64_t> PatchMesh::nodeKeys(uint32_t node, int levels) const {
  const PatchNode& n = nodes_[node];
  const int below = 2 * std::max(0, finestDepth(n.root, levels) - int(n.depth));
  const uint64_t root = uint64_t(n.root) << 32;
  return {root | (uint64_t(n.path) << below), root | (uint64_t(n.path + 1) << below)};
}

uint64_t PatchMesh::nodeAddress(uint32_t node) const {
  const PatchNode& n = nodes_[node];
  return (uint64_t(n.root) << 32) | (uint64_t(n.depth) << 24) | n.path;
}

Vec3 PatchMesh::samplePoint(uint32_t patch, Vec2 u, float& weight) const {
  std::array<Vec3, 4> c;
  if (corners(patch, c) == 3) {
    const Vec2 b = sampleUniformTriangle(u);  // weights of c[0] and c[2]
    weight = 1.0f;
    return b.x * c[0] + (1.0f - b.x - b.y) * c[1] + b.y * c[2];
  }
  const Vec3 du = (1 - u.y) * (c[1] - c[0]) + u.y * (c[2] - c[3]);
  const Vec3 dv = (1 - u.x) * (c[3] - c[0]) + u.x * (c[2] - c[1]);
  weight = glm::length(glm::cross(du, dv)) / std::max(patches_[patch].area, 1e-30f);
  return (1 - u.x) * (1 - u.y) * c[0] + u.x * (1 - u.y) * c[1] + u.x * u.y * c[2] +
         (1 - u.x) * u.y * c[3];
}

size_t PatchMesh::memoryBytes() const {
  return vertices_.size() * 2 * sizeof(Vec3) + nodes_.size() * sizeof(PatchNode) +
         roots_.size() * sizeof(PatchRoot) + patches_.size() * sizeof(Patch) +
         triangleRoot_.size() * sizeof(uint32_t);
}

}  // namespace rad
