#pragma once
// The patches of the patch method: every planar face of the scene subdivided by a quadtree
// (quads into 4 quads by their bilinear map, triangles into 4 by their edge midpoints) until each
// patch's longest edge is at most the patch size (the base level). Every node keeps its parent,
// children and a unique id (its index); refine() splits chosen leaves further (adaptive
// subdivision), which leaves hanging vertices where a fine patch meets a coarse one
// (hangingVertices). Corners are welded across patches (same position, normals within the crease
// angle) so that values averaged at vertices shade smoothly. Two-sided faces get a second,
// mirrored set of patches for their back.

#include <radiosity/scene.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

namespace rad {

inline constexpr uint32_t kNoPatch = ~0u;
inline constexpr uint32_t kNoNode = ~0u;
inline constexpr uint64_t kNoKey = ~0ull;
/// The deepest a quadtree goes (2 bits a level of a node's path: 24 bits).
inline constexpr int kMaxPatchDepth = 12;

struct PatchNode {
  std::array<uint32_t, 4> corners{};  ///< welded vertex ids, CCW about the side's normal
  uint32_t parent = kNoNode;
  uint32_t firstChild = kNoNode;  ///< children are the 4 nodes from here on
  uint32_t root = 0;              ///< the PatchRoot this node descends from
  uint32_t patch = kNoPatch;      ///< leaf: its patch index
  uint32_t path = 0;  ///< child indices from the root down, 2 bits a level, the root's first
  uint8_t depth = 0;
  bool quad = true;  ///< 4 corners (bilinear) or 3 (corners[3] unused)

  bool leaf() const { return firstChild == kNoNode; }
  int cornerCount() const { return quad ? 4 : 3; }
};

/// A quadtree's top: a whole convex quad face, or one triangle of any other face; one per side.
struct PatchRoot {
  uint32_t face = 0;
  uint32_t node = 0;
  bool back = false;      ///< the mirrored back side of a two-sided face
  uint8_t baseDepth = 0;  ///< depth of the base level's leaves (before refinement)
  /// The scene triangles it covers: its face's two (a quad) or the one it was made from.
  uint32_t firstTriangle = 0, triangleCount = 0;
};

/// A vertex in the middle of a leaf's edge (a, b) that is not that leaf's corner: a finer
/// neighbour's corner. Values there must be the edge's mean for shading without cracks.
struct HangingVertex {
  uint32_t vertex = 0, a = 0, b = 0;
};

/// A leaf of the quadtree: the unit the radiosity equation is solved on.
struct Patch {
  uint32_t node = 0;
  uint32_t face = 0;
  uint32_t object = 0;
  uint32_t material = 0;
  float area = 0.0f;
  Vec3 centroid{0.0f};
  Vec3 normal{0.0f};         ///< unit normal of the side the patch emits and receives on
  Color rho{0.0f};           ///< its material's reflectance times the texture's mean over it
  Color emissionTint{1.0f};  ///< the emission texture's mean over it (1: none)
  /// Its material's mean coverage over it (Scene::coverageAt; 1: opaque). rho and the emission
  /// tint are means weighted by coverage: what its covered part reflects and emits.
  float coverage = 1.0f;

  /// The area that reflects and emits, A c: what reciprocity (A_i F_ij = A_j F_ji) and the
  /// power balance weigh a patch by. Never 0 (a patch cut away whole keeps a millionth of its
  /// area, which no ray finds), so that ratios of areas stay finite.
  float coveredArea() const { return area * std::max(coverage, 1e-6f); }
};

struct PatchMeshSettings {
  float patchSize = 0.0f;       ///< longest patch edge in scene units; 0: from targetPatches
  size_t targetPatches = 4000;  ///< approximate patch count when patchSize is 0
};

class PatchMesh {
 public:
  /// Throws InputError for a negative or non-finite patch size.
  PatchMesh(const Scene& scene, const PatchMeshSettings& settings);

  /// The longest-edge limit that gives about `target` patches beyond the one each face root
  /// makes at least (never more than 4x them).
  static float patchSizeFor(const Scene& scene, size_t target);
  /// The number of base patches a patch size gives, counted without meshing.
  static double patchCountFor(const Scene& scene, float patchSize);

  float patchSize() const { return patchSize_; }
  const std::vector<Vec3>& vertices() const { return vertices_; }
  const std::vector<Vec3>& vertexNormals() const { return vertexNormals_; }
  const std::vector<PatchNode>& nodes() const { return nodes_; }
  const std::vector<PatchRoot>& roots() const { return roots_; }
  const std::vector<Patch>& patches() const { return patches_; }
  size_t size() const { return patches_.size(); }
  const PatchNode& nodeOf(uint32_t patch) const { return nodes_[patches_[patch].node]; }

  /// The corner positions of a patch (3 or 4), CCW about its normal.
  int corners(uint32_t patch, std::array<Vec3, 4>& out) const;

  /// Where a surface point lies: its patch and the interpolation weights of that patch's corners
  /// (bilinear in a quad, barycentric in a triangle). patch is kNoPatch on the back of a
  /// one-sided face.
  struct Location {
    uint32_t patch = kNoPatch;
    std::array<float, 4> weights{};
  };
  Location locate(uint32_t triangle, bool frontFace, const Vec3& point) const;

  /// Where a surface point lies in the quadtree as deep as refinement may ever go (`levels`
  /// below each root's base depth, at most kMaxPatchDepth): its root and path there, whether or
  /// not those nodes exist. A node covers the points whose finest key lies in nodeKeys(node).
  /// kNoKey on the back of a one-sided face.
  uint64_t finestKey(uint32_t triangle, bool frontFace, const Vec3& point, int levels) const;
  /// The finest keys [first, last) that `node` covers.
  std::pair<uint64_t, uint64_t> nodeKeys(uint32_t node, int levels) const;
  /// A name for a node that does not depend on the order nodes were made in: its root, depth and
  /// path (so that tables of rows by node outlive the mesh that made them).
  uint64_t nodeAddress(uint32_t node) const;

  /// A point of the patch for u in [0,1)^2, and its weight (the bilinear map's area density over
  /// its mean; 1 for triangles, whose map is area-preserving): average weight x f estimates the
  /// area mean of f.
  Vec3 samplePoint(uint32_t patch, Vec2 u, float& weight) const;

  /// Splits each listed patch one level into 4 (patches deeper than kMaxDepth stay). Patch
  /// indices change (the leaves in depth-first order, as the constructor numbers them); node
  /// ids do not.
  void refine(std::span<const uint32_t> patches);
  /// Refines until the patches are the nodes at `addresses` (nodeAddress; a refined mesh's
  /// patches, saved). False, part way, where they are not the leaves of a refinement of this
  /// mesh: a patch would have to split without any of them below it.
  bool refineToLeaves(std::span<const uint64_t> addresses);
  /// True if refine() has split any patch.
  bool refined() const { return refined_; }
  /// Every hanging vertex, coarser edges first, so that assigning each the mean of its edge's
  /// ends in this order is right where those ends hang themselves.
  std::vector<HangingVertex> hangingVertices() const;

  /// The coverage at a point of the patch (Scene::coverageAt at the scene triangle under it).
  float coverageAt(uint32_t patch, const Vec3& point) const;
  /// True if the coverage is the same over the whole patch (its material's alpha reads no
  /// texture or vertex alpha): then coverageAt is its mean everywhere.
  bool uniformCoverage(uint32_t patch) const;

  /// Distance by which sample points are lifted off their surface before a ray leaves them.
  float rayOffset() const { return weldCell_ * 20.0f; }

  /// Bytes held by the mesh arrays.
  size_t memoryBytes() const;

 private:
  void addRoot(uint32_t face, bool back, std::span<const uint32_t> corners);
  /// A point's coordinates in the root node `root`: (u, v) for a quad, barycentrics otherwise.
  struct RootPoint {
    Vec2 uv{0.0f};
    Vec3 w{0.0f};
  };
  RootPoint rootPoint(uint32_t root, const Vec3& point) const;
  int finestDepth(uint32_t root, int levels) const;
  void subdivide(uint32_t node, int depth, const Vec3& normal);
  uint32_t weldedVertex(const Vec3& p, const Vec3& normal);
  /// The welded vertex at p for `normal`, or kNoNode.
  uint32_t findVertex(const Vec3& p, const Vec3& normal) const;
  static uint64_t weldKey(const Vec3& p, float cell);
  void finishPatch(uint32_t node);
  void applyMaterialMeans(uint32_t patch);
  void numberPatches();

  const Scene* scene_;
  float patchSize_ = 0.0f;
  float weldCell_ = 0.0f;
  std::vector<Vec3> vertices_, vertexNormals_;
  std::vector<PatchNode> nodes_;
  std::vector<PatchRoot> roots_;
  std::vector<Patch> patches_;
  std::vector<uint32_t> triangleRoot_;  ///< per scene triangle and side: 2 t + back
  std::unordered_map<uint64_t, std::vector<uint32_t>> weld_;  ///< kept for refine()
  bool refined_ = false;
};

}  // namespace rad
