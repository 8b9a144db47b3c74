#include "output/lightmap_atlas.h"

#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/process_memory.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

// stb_rect_pack's implementation, compiled here once.
#define STB_RECT_PACK_IMPLEMENTATION
#include <stb_rect_pack.h>

namespace rad {

namespace {

// A face in its own plane: axes and the extent of its triangles along them (scene units).
struct FacePlane {
  Vec3 origin{0.0f}, uAxis{0.0f}, vAxis{0.0f};
  Vec2 lo{0.0f}, hi{0.0f};
};

FacePlane planeOf(const Scene& scene, const Face& face) {
  FacePlane plane;
  const UVec3& first = scene.triangles[face.firstTriangle];
  const Vec3 p0 = scene.positions[first[0]];
  // Axes along the face's first edge: a rectangle's chart is then a rectangle, not a
  // diamond that wastes half its texels.
  Vec3 u = scene.positions[first[1]] - p0;
  u -= face.normal * glm::dot(u, face.normal);
  plane.uAxis = glm::normalize(u);
  plane.vAxis = glm::cross(face.normal, plane.uAxis);
  plane.lo = Vec2(std::numeric_limits<float>::max());
  plane.hi = Vec2(-std::numeric_limits<float>::max());
  for (uint32_t t = face.firstTriangle; t < face.firstTriangle + face.triangleCount; ++t)
    for (int k = 0; k < 3; ++k) {
      const Vec3 d = scene.positions[scene.triangles[t][k]] - p0;
      const Vec2 q(glm::dot(d, plane.uAxis), glm::dot(d, plane.vAxis));
      plane.lo = glm::min(plane.lo, q);
      plane.hi = glm::max(plane.hi, q);
    }
  plane.origin = p0 + plane.uAxis * plane.lo.x + plane.vAxis * plane.lo.y;
  return plane;
}

// Texels a chart spans along an extent: the face's own, at least one, and a gutter each side.
int chartTexels(float extent, float texelsPerUnit) {
  const double inner = std::ceil(double(extent) * texelsPerUnit);
  return int(std::clamp(inner, 1.0, 1e8)) + 2 * LightmapAtlas::kGutter;
}

// Packs charts of the given extents at `texelsPerUnit`; false when they do not all fit.
bool packAt(std::vector<LightmapChart>& charts, const std::vector<Vec2>& extents, int size,
            float texelsPerUnit) {
  std::vector<stbrp_rect> rects(charts.size());
  for (size_t i = 0; i < charts.size(); ++i) {
    rects[i].id = int(i);
    rects[i].w = chartTexels(extents[i].x, texelsPerUnit);
    rects[i].h = chartTexels(extents[i].y, texelsPerUnit);
    if (rects[i].w > size || rects[i].h > size) return false;
  }
  std::vector<stbrp_node> nodes(static_cast<size_t>(size));
  stbrp_context context;
  stbrp_init_target(&context, size, size, nodes.data(), size);
  if (!stbrp_pack_rects(&context, rects.data(), int(rects.size()))) return false;
  for (const stbrp_rect& r : rects) {
    LightmapChart& c = charts[size_t(r.id)];
    c.x = r.x;
    c.y = r.y;
    c.width = r.w;
    c.height = r.h;
  }
  return true;
}

}  // namespace

Vec2 LightmapAtlas::texcoordOf(const LightmapChart& chart, const Vec3& point) const {
  const Vec3 d = point - chart.origin;
  const float x = float(chart.x + kGutter) + glm::dot(d, chart.uAxis) * texelsPerUnit;
  const float y = float(chart.y + kGutter) + glm::dot(d, chart.vAxis) * texelsPerUnit;
  return Vec2(x, y) / float(size);
}

namespace {

// A chart for the front of every face and the back of two-sided ones, unplaced, with the
// extents of their faces in their planes.
struct UnplacedCharts {
  std::vector<LightmapChart> charts;
  std::vector<Vec2> extents;
  double area = 0.0;
  float largestExtent = 0.0f;
};

UnplacedCharts chartsOf(const Scene& scene) {
  UnplacedCharts out;
  for (uint32_t f = 0; f < scene.faces.size(); ++f) {
    const Face& face = scene.faces[f];
    if (face.triangleCount == 0) continue;
    const FacePlane plane = planeOf(scene, face);
    const int sides = scene.materials[face.material].twoSided ? 2 : 1;
    for (int side = 0; side < sides; ++side) {
      out.charts.push_back({f, side == 1, 0, 0, 0, 0, plane.origin, plane.uAxis, plane.vAxis});
      const Vec2 extent = plane.hi - plane.lo;
      out.extents.push_back(extent);
      out.area += double(extent.x) * extent.y;
      out.largestExtent = std::max({out.largestExtent, extent.x, extent.y});
    }
  }
  return out;
}

// Packs the charts at their smallest (every one 5 x 5 texels), or refuses the size.
void packSmallest(UnplacedCharts& c, int size) {
  if (!c.charts.empty() && packAt(c.charts, c.extents, size, 0.0f)) return;
  const int smallest = chartTexels(0.0f, 0.0f);
  throw InputError("--lightmap " + std::to_string(size),
                   fmt::format("an atlas of {} x {} texels cannot hold the {} charts of this "
                               "scene ({} x {} texels at least each); give a larger size",
                               size, size, c.charts.size(), smallest, smallest));
}

}  // namespace

void requireLightmapExport(const Scene& scene, int size) {
  requireMemory(double(size) * size * kLightmapBytesPerTexel, "--lightmap",
                fmt::format("a lightmap atlas of {0} x {0} texels", size), "give a smaller size");
  UnplacedCharts c = chartsOf(scene);
  packSmallest(c, size);
}

LightmapAtlas packLightmapAtlas(const Scene& scene, int size) {
  UnplacedCharts c = chartsOf(scene);
  packSmallest(c, size);
  LightmapAtlas atlas;
  atlas.size = size;
  atlas.charts = c.charts;  // the smallest layout, until a denser one packs
  // From the density at which the charts' areas alone would fill the atlas, shrink until they
  // pack (or are all at their smallest), then bisect between the last that failed and the
  // first that fits: 3 steps leave the density within 3% of the largest.
  // At 1 / largestExtent every chart is at its smallest: the layout packSmallest found.
  float fits = c.largestExtent > 0.0f ? 1.0f / c.largestExtent : 1.0f;
  float fails = float(std::sqrt(double(size) * size / std::max(c.area, 1e-30)));
  for (float t = fails; t > fits; t *= 0.7f) {
    if (packAt(c.charts, c.extents, size, t)) {
      fits = t;
      atlas.charts = c.charts;
      break;
    }
    fails = t;
  }
  for (int step = 0; step < 3 && fails > fits; ++step) {
    const float t = 0.5f * (fits + fails);
    if (!packAt(c.charts, c.extents, size, t)) {
      fails = t;
      continue;
    }
    fits = t;
    atlas.charts = c.charts;
  }
  atlas.texelsPerUnit = fits;
  return atlas;
}

namespace {

// The point at barycentrics `b` of `triangle` (clamped onto it), as a surface hit on the chart's
// side.
SurfaceHit hitOn(const Scene& scene, const LightmapChart& chart, uint32_t triangle, Vec2 b) {
  b = glm::max(b, Vec2(0.0f));
  if (b.x + b.y > 1.0f) b /= b.x + b.y;
  const UVec3& t = scene.triangles[triangle];
  SurfaceHit hit;
  hit.point = (1.0f - b.x - b.y) * scene.positions[t[0]] + b.x * scene.positions[t[1]] +
              b.y * scene.positions[t[2]];
  hit.normal = scene.faces[chart.face].normal;
  hit.triangle = triangle;
  hit.frontFace = !chart.backSide;
  hit.barycentric = b;
  return hit;
}

}  // namespace

LightmapImages shadeLightmapAtlas(const LightmapAtlas& atlas, const SurfaceSolution& solution) {
  const Scene& scene = solution.scene();
  LightmapImages images{Image(atlas.size, atlas.size), Image(atlas.size, atlas.size)};
  tbb::parallel_for(size_t(0), atlas.charts.size(), [&](size_t i) {
    const LightmapChart& c = atlas.charts[i];
    auto shade = [&](int x, int y, const SurfaceHit& hit) {
      images.irradiance.at(c.x + x, c.y + y) = solution.irradiance(hit);
      images.radiance.at(c.x + x, c.y + y) = solution.radiance(hit);
    };
    // The texel's centre, in the face's plane.
    auto centre = [&](int x, int y) {
      const float u = (float(x - LightmapAtlas::kGutter) + 0.5f) / atlas.texelsPerUnit;
      const float v = (float(y - LightmapAtlas::kGutter) + 0.5f) / atlas.texelsPerUnit;
      return c.origin + c.uAxis * u + c.vAxis * v;
    };
    // Triangle by triangle, the texels whose centres lie on it; then the rest (the gutters, the
    // outline's outside) from the nearest point of the face, a search through its triangles.
    std::vector<uint8_t> done(size_t(c.width) * size_t(c.height), 0);
    const Face& face = scene.faces[c.face];
    for (uint32_t t = face.firstTriangle; t < face.firstTriangle + face.triangleCount; ++t) {
      Vec2 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
      for (int k = 0; k < 3; ++k) {
        const Vec2 texel =
            atlas.texcoordOf(c, scene.positions[scene.triangles[t][k]]) * float(atlas.size) -
            Vec2(float(c.x), float(c.y));
        lo = glm::min(lo, texel);
        hi = glm::max(hi, texel);
      }
      for (int y = std::max(0, int(lo.y)); y <= std::min(c.height - 1, int(hi.y)); ++y)
        for (int x = std::max(0, int(lo.x)); x <= std::min(c.width - 1, int(hi.x)); ++x) {
          const size_t k = size_t(y) * size_t(c.width) + size_t(x);
          if (done[k]) continue;
          const Vec2 b = scene.barycentricOf(t, centre(x, y));
          if (std::min({b.x, b.y, 1.0f - b.x - b.y}) < 0.0f) continue;
          shade(x, y, hitOn(scene, c, t, b));
          done[k] = 1;
        }
    }
    for (int y = 0; y < c.height; ++y)
      for (int x = 0; x < c.width; ++x) {
        if (done[size_t(y) * size_t(c.width) + size_t(x)]) continue;
        uint32_t triangle = 0;
        const Vec2 b = scene.locateOnFace(c.face, centre(x, y), triangle);
        shade(x, y, hitOn(scene, c, triangle, b));
      }
  });
  return images;
}

LitMesh lightmappedMesh(const Scene& scene, const LightmapAtlas& atlas) {
  LitMesh mesh;
  // Charts by object, so that each object's triangles form one run (one glTF node).
  std::vector<std::vector<uint32_t>> chartsOfObject(scene.objects.size());
  for (uint32_t i = 0; i < atlas.charts.size(); ++i)
    chartsOfObject[scene.faces[atlas.charts[i].face].object].push_back(i);
  for (uint32_t o = 0; o < scene.objects.size(); ++o) {
    LitMeshGroup group{scene.objects[o].name, uint32_t(mesh.indices.size() / 3), 0};
    for (uint32_t i : chartsOfObject[o]) {
      const LightmapChart& chart = atlas.charts[i];
      const Face& face = scene.faces[chart.face];
      const Vec3 normal = chart.backSide ? -face.normal : face.normal;
      std::vector<std::pair<uint32_t, uint32_t>> vertexOf;  // scene position -> mesh vertex
      auto vertex = [&](uint32_t position) {
        for (const auto& [p, v] : vertexOf)
          if (p == position) return v;
        const uint32_t v = uint32_t(mesh.positions.size());
        mesh.positions.push_back(scene.positions[position]);
        mesh.normals.push_back(normal);
        mesh.colors.emplace_back(0.0f);
        mesh.lightmapTexcoords.push_back(atlas.texcoordOf(chart, scene.positions[position]));
        vertexOf.emplace_back(position, v);
        return v;
      };
      for (uint32_t t = face.firstTriangle; t < face.firstTriangle + face.triangleCount; ++t) {
        const UVec3& tri = scene.triangles[t];
        const uint32_t a = vertex(tri[0]), b = vertex(tri[1]), c = vertex(tri[2]);
        if (chart.backSide)
          mesh.indices.insert(mesh.indices.end(), {a, c, b});
        else
          mesh.indices.insert(mesh.indices.end(), {a, b, c});
        ++group.triangleCount;
      }
    }
    if (group.triangleCount > 0) mesh.groups.push_back(group);
  }
  return mesh;
}

}  // namespace rad
