#pragma once
// What every radiosity method's solution offers beyond radiance: its surface elements (patches
// or voxel sides) and the lit mesh a viewer shows. The per-object statistics and the exporters
// are written once, against this interface, for every method.

#include <radiosity/light_groups.h>
#include <radiosity/object_radiometry.h>
#include <radiosity/scene.h>
#include <radiosity/surface_radiance.h>

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace rad {

/// One element of a solution: a patch, or a voxel side.
struct SurfaceElement {
  uint32_t object = 0;
  float area = 0.0f;
  Vec3 position{0.0f};
  Vec3 normal{0.0f};
  Color emitted{0.0f};  ///< E = pi Ke, radiosity emitted
  Color rho{0.0f};
  Color irradiance{0.0f};  ///< H
  Color radiosity{0.0f};   ///< B = E + rho H
  bool backSide = false;   ///< the back of a two-sided face
};

/// A run of triangles written as one glTF node (and mesh), named e.g. after a scene object.
struct LitMeshGroup {
  std::string name;
  uint32_t firstTriangle = 0;
  uint32_t triangleCount = 0;
};

/// A texture a lit mesh's triangles show: their colours are then the light a white surface
/// would send there (irradiance / pi), which the texture times its factor multiplies (glTF's
/// COLOR_0 times the base colour), so that an engine shows the texture's detail.
struct LitMeshTexture {
  std::string name;
  std::shared_ptr<const Texture> texture;
  TextureWrap wrapU = TextureWrap::Repeat, wrapV = TextureWrap::Repeat;
  Color factor{1.0f};
};

/// A lit triangle mesh: the solved light baked into vertex colours.
struct LitMesh {
  std::vector<Vec3> positions;  ///< scene units
  std::vector<Vec3> normals;    ///< per vertex; normalised on write
  std::vector<Color> colors;    ///< linear RGB per vertex; clamped to [0, 1] on write
  /// Per vertex, its texture coordinates (its texture's transform applied); empty: no textures.
  std::vector<Vec2> texcoords;
  std::vector<LitMeshTexture> textures;
  /// Per triangle, its index in `textures`, or kUntextured (colours are the outgoing radiance);
  /// empty: no triangle is textured.
  std::vector<uint32_t> triangleTextures;
  static constexpr uint32_t kUntextured = UINT32_MAX;
  /// Per vertex, its place in a lightmap atlas (glTF's TEXCOORD_1); empty: no lightmap, the
  /// colours are the light.
  std::vector<Vec2> lightmapTexcoords;
  /// 3 per triangle, CCW about the side it shows (one-sided: a surface seen from both sides
  /// has a triangle for each, with that side's light).
  std::vector<uint32_t> indices;
  /// Triangle ranges, one node each; empty: a single node "radiosity" with every triangle.
  std::vector<LitMeshGroup> groups;
};

/// A method's account of a solve: what a command prints and the stats file records.
struct SolveReport {
  /// The numbers of the run in a line, e.g. "4012 patches, form factors 1.2 s, ... residual 8e-4".
  std::string summary;
  /// The stats' counts (docs/ARCHITECTURE.md, "Stats JSON"): those the method has.
  uint64_t patches = 0, voxels = 0, directions = 0, rays = 0;
  double prepareSeconds = 0.0;  ///< once per geometry: meshing, voxelizing, form factors
  double solveSeconds = 0.0;    ///< per light state: the lights' direct light and the bounces
  int iterations = 0;
  std::vector<double> residuals;  ///< relative residual per iteration
  bool converged = false;         ///< the last residual fell below the tolerance
  std::vector<std::string> warnings;
  std::string resumed;  ///< what a checkpoint brought, said to the user; empty: nothing
  /// The longest edge of triangles that show the solution's detail (a viewer's display mesh),
  /// in scene units; 0: no size of its own.
  float detailEdge = 0.0f;
  /// The numbers particular to the method, a JSON object (the stats' entry under its name).
  std::string detailsJson = "{}";
};

class SurfaceSolution : public SurfaceRadiance {
 public:
  /// The scene it solves.
  virtual const Scene& scene() const = 0;
  /// Its elements, made one at a time (a voxel solution holds millions).
  virtual size_t elementCount() const = 0;
  virtual SurfaceElement element(size_t index) const = 0;
  /// The mesh that shows it: vertex colours the radiance radiance() gives there.
  virtual LitMesh litMesh() const = 0;
  /// The irradiance H at `hit` (power per area arriving, W per square scene unit), interpolated
  /// as radiance() interpolates it: what a lighting designer's false-colour view shows. 0 on the
  /// back of a one-sided face.
  virtual Color irradiance(const SurfaceHit& hit) const = 0;

  /// The light groups it solved apart (empty: its emitters were solved together).
  virtual std::span<const LightGroup> lightGroups() const { return {}; }
  /// The scale each group's light has now (1 each until set).
  virtual std::span<const Color> groupScales() const { return {}; }
  /// Combines the groups' solutions anew, each times its scale (RGB, finite, >= 0; 0 switches a
  /// group off): the full multi-bounce answer for the dimmed, tinted or switched lights, without
  /// a solve. Throws std::invalid_argument unless there is one scale per group.
  virtual void setGroupScales(std::span<const Color> scales);
  /// Element `index`'s radiosity from group `group`'s light alone, at its current scale.
  virtual Color groupRadiosity(size_t group, size_t index) const;

  /// What the solve did (SolveReport); an empty report for a solution that keeps none.
  virtual SolveReport report() const { return {}; }
  /// Writes the solution file `path` (solution_file.h), atomically, recording `settings` (those
  /// it was solved with) so that the same method and settings load it. Throws std::logic_error
  /// for a method without the saveSolution capability, std::runtime_error if it cannot be
  /// written.
  virtual void save(const std::string& path, const SolverSettings& settings) const;

  /// Area-weighted means over the front-side elements of each scene object (with light groups,
  /// each group's share of its radiosity).
  std::vector<ObjectRadiometry> objectRadiometry() const;
  /// One row per element (the CSV columns of docs/ARCHITECTURE.md), written atomically.
  void exportCsv(const std::string& path) const;
  /// A binary PLY point cloud: position, normal, sRGB colour of B / pi x 2^exposureEV,
  /// radiosity B.
  void exportPly(const std::string& path, float exposureEV = 0.0f) const;
  /// litMesh() as binary glTF 2.0 (.glb), written atomically: one node per scene object,
  /// COLOR_0 the radiance x 2^exposureEV, linear and clamped to [0, 1], under an unlit white
  /// material; the asset's extras say which exposure.
  void exportGlb(const std::string& path, float exposureEV = 0.0f) const;
  /// The scene's own triangles as binary glTF 2.0 with a lightmap atlas of `size` x `size`
  /// texels (a chart per face side, TEXCOORD_1): `path`, showing the outgoing radiance
  /// x 2^exposureEV through an unlit material, and beside it, for engines, the irradiance atlas
  /// as a float EXR (lightmapIrradiancePath(path)), which the .glb's extras name. Both written
  /// atomically. Throws InputError when the scene's charts do not fit in `size`.
  void exportLightmappedGlb(const std::string& path, int size, float exposureEV = 0.0f) const;
};

/// Refuses a lightmap atlas of `size` x `size` texels before a long solve, at the cost of one
/// packing: throws InputError when its images would not fit in the memory left or the scene's
/// charts do not fit in it (exportLightmappedGlb would refuse the same after the solve).
void requireLightmapExport(const Scene& scene, int size);

/// Where exportLightmappedGlb puts the irradiance atlas of `glbPath`: its extension replaced by
/// ".lightmap.exr".
std::string lightmapIrradiancePath(const std::string& glbPath);

/// The largest difference of two solutions' element radiosity (any channel), relative to the
/// area-mean radiosity of `reference` (over its channels): how far `solution` is from it, as
/// relighting is judged against a fresh solve. Both must have the same elements in the same
/// order; throws std::invalid_argument when their counts differ.
double largestRadiosityDifference(const SurfaceSolution& solution,
                                  const SurfaceSolution& reference);

}  // namespace rad
