#include "voxel/voxelizer.h"

#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/process_memory.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cassert>
#include <cmath>
#include <map>
#include <tuple>

#include "core/vector_memory.h"
#include "voxel/half_float.h"

namespace rad {

namespace {

// A convex polygon clipped from a triangle by at most 6 planes has at most 9 corners.
struct ClipPolygon {
  std::array<Vec3d, 12> p;
  int n = 0;
};

// Sutherland-Hodgman against lo <= x[axis] <= hi (closed, so touching counts).
ClipPolygon clipToSlab(const ClipPolygon& in, int axis, double lo, double hi) {
  ClipPolygon tmp, out;
  auto clip = [axis](const ClipPolygon& src, ClipPolygon& dst, double bound, double sign) {
    dst.n = 0;
    for (int i = 0; i < src.n; ++i) {
      const Vec3d& a = src.p[i];
      const Vec3d& b = src.p[(i + 1) % src.n];
      const double da = sign * (a[axis] - bound), db = sign * (b[axis] - bound);
      if (da >= 0.0) dst.p[dst.n++] = a;
      if ((da >= 0.0) != (db >= 0.0)) dst.p[dst.n++] = a + (b - a) * (da / (da - db));
    }
  };
  clip(in, tmp, lo, 1.0);
  clip(tmp, out, hi, -1.0);
  return out;
}

double polygonArea(const ClipPolygon& poly, Vec3d& centroid) {
  Vec3d cross(0.0);
  Vec3d weighted(0.0);
  double area2 = 0.0;
  for (int i = 1; i + 1 < poly.n; ++i) {
    const Vec3d c = glm::cross(poly.p[i] - poly.p[0], poly.p[i + 1] - poly.p[0]);
    const double a = glm::length(c);
    cross += c;
    area2 += a;
    weighted += a * (poly.p[0] + poly.p[i] + poly.p[i + 1]) / 3.0;
  }
  centroid = area2 > 0.0 ? weighted / area2 : poly.p[0];
  return 0.5 * glm::length(cross);
}

// A piece of one triangle side inside one voxel.
struct Fragment {
  uint64_t cellKey;
  uint32_t triangle;
  float area;
  Vec3 centroid;
  bool backSide;
};

uint64_t cellKey(int x, int y, int z) {
  return (uint64_t(uint16_t(x)) << 32) | (uint64_t(uint16_t(y)) << 16) | uint64_t(uint16_t(z));
}

IVec3 keyCell(uint64_t key) {
  return IVec3(int((key >> 32) & 0xffff), int((key >> 16) & 0xffff), int(key & 0xffff));
}

// Where a triangle's fragments go once their count is known: their place in the array of all.
struct FragmentSpan {
  Fragment* data;
  size_t count = 0;
  size_t size() const { return count; }
  void push_back(const Fragment& f) { data[count++] = f; }
  Fragment& operator[](size_t i) { return data[i]; }
  Fragment& back() { return data[count - 1]; }
};

// Pieces of triangle t: slab by slab, row by row, so work follows the surface, not its box.
// `out` is a vector (to count them) or their span in the array of all.
template <typename Out>
void fragmentTriangle(const Scene& scene, const VoxelGrid& grid, uint32_t t, bool twoSided,
                      Out& out) {
  const double s = grid.voxelSize, eps = 1e-4 * s;
  const Vec3d origin(grid.origin);
  ClipPolygon tri;
  tri.n = 3;
  for (int k = 0; k < 3; ++k) tri.p[k] = Vec3d(scene.positions[scene.triangles[t][k]]) - origin;
  Vec3d lo(tri.p[0]), hi(tri.p[0]);
  for (int k = 1; k < 3; ++k) lo = glm::min(lo, tri.p[k]), hi = glm::max(hi, tri.p[k]);
  auto cellRange = [&](double a, double b, int axis, int& first, int& last) {
    first = std::max(0, int(std::floor((a - eps) / s)));
    last = std::min(grid.dims[axis] - 1, int(std::floor((b + eps) / s)));
  };
  const size_t begin = out.size();
  double total = 0.0;
  int x0, x1;
  cellRange(lo.x, hi.x, 0, x0, x1);
  for (int x = x0; x <= x1; ++x) {
    const ClipPolygon slab = clipToSlab(tri, 0, x * s - eps, (x + 1) * s + eps);
    if (slab.n == 0) continue;
    double ylo = slab.p[0].y, yhi = ylo;
    for (int i = 1; i < slab.n; ++i)
      ylo = std::min(ylo, slab.p[i].y), yhi = std::max(yhi, slab.p[i].y);
    int y0, y1;
    cellRange(ylo, yhi, 1, y0, y1);
    for (int y = y0; y <= y1; ++y) {
      const ClipPolygon row = clipToSlab(slab, 1, y * s - eps, (y + 1) * s + eps);
      if (row.n == 0) continue;
      double zlo = row.p[0].z, zhi = zlo;
      for (int i = 1; i < row.n; ++i)
        zlo = std::min(zlo, row.p[i].z), zhi = std::max(zhi, row.p[i].z);
      int z0, z1;
      cellRange(zlo, zhi, 2, z0, z1);
      for (int z = z0; z <= z1; ++z) {
        const ClipPolygon cell = clipToSlab(row, 2, z * s - eps, (z + 1) * s + eps);
        if (cell.n == 0) continue;
        Vec3d centroid;
        const double area = polygonArea(cell, centroid);
        total += area;
        out.push_back({cellKey(x, y, z), t, float(area), Vec3(centroid + origin), false});
      }
    }
  }
  // The tolerance counts pieces on shared cube faces twice: scale to the triangle's exact area.
  const double scale = total > 0.0 ? scene.triangleArea(t) / total : 0.0;
  const size_t end = out.size();
  for (size_t i = begin; i < end; ++i) {
    out[i].area = float(out[i].area * scale);
    if (twoSided) {
      out.push_back(out[i]);
      out.back().backSide = true;
    }
  }
}

// The sides of one cell: its fragments clustered by normal. Pieces within 60 degrees of each
// other share an orientation (a curved or folded surface); a wall's back or a corner's other face
// does not. Within an orientation each scene object keeps its own side, so that per-object
// results stay exact where objects meet (a lamp set in a ceiling).
struct Side {
  uint32_t orientation = 0, object = 0;
  uint32_t id = 0;  ///< its place among its cell's sides as they were made
  Vec3d normalSum{0.0}, centroidSum{0.0}, rhoArea{0.0}, keArea{0.0};
  double weight = 0.0, area = 0.0, backArea = 0.0;
  double coveredArea = 0.0, coveredWeight = 0.0;  ///< area times coverage (Material)
  uint32_t emitter = VoxelSurface::kNoEmitter;    ///< the material of the most emission so far
  double emitterWeight = 0.0;
};

// A piece's mean coverage: its value where it is uniform, else the mean of 3 x 3 points around
// the centroid in the triangle's plane, over the piece's size (a voxel's piece of a cut-out
// leaf spans several texels).
float pieceCoverage(const Scene& scene, const Fragment& f) {
  const uint32_t t = f.triangle;
  if (scene.uniformCoverage(t)) return scene.coverageAt(t, Vec2(1.0f / 3.0f));
  const Vec3 n = scene.triangleNormal(t);
  const Vec3 u =
      glm::normalize(glm::cross(n, std::abs(n.x) < 0.9f ? Vec3(1, 0, 0) : Vec3(0, 1, 0)));
  const Vec3 v = glm::cross(n, u);
  const float step = std::sqrt(std::max(f.area, 0.0f)) / 3.0f;
  float sum = 0.0f;
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j) {
      const Vec3 p = f.centroid + step * (float(i) * u + float(j) * v);
      sum += scene.coverageAt(t, scene.barycentricOf(t, p));
    }
  return sum / 9.0f;
}

Vec3 fragmentNormal(const Scene& scene, const Fragment& f) {
  return f.backSide ? -scene.triangleNormal(f.triangle) : scene.triangleNormal(f.triangle);
}

// Adds the piece to the side of its orientation and object; returns that side's id.
uint32_t addToSides(const Scene& scene, const Fragment& f, std::vector<Vec3d>& orientations,
                    std::vector<Side>& sides) {
  const Vec3 n = fragmentNormal(scene, f);
  uint32_t orientation = uint32_t(orientations.size());
  for (uint32_t o = 0; o < orientations.size(); ++o)
    if (glm::dot(glm::normalize(orientations[o]), Vec3d(n)) > 0.5) orientation = o;
  if (orientation == orientations.size()) orientations.emplace_back(0.0);
  const uint32_t object = scene.faceOf(f.triangle).object;
  auto side = std::find_if(sides.begin(), sides.end(), [&](const Side& s) {
    return s.orientation == orientation && s.object == object;
  });
  if (side == sides.end())
    side = sides.insert(sides.end(), Side{orientation, object, uint32_t(sides.size())});
  // Pieces that only touch the cube (zero area) still orient and place the side.
  const double w = std::max(double(f.area), 1e-12);
  const Material& m = scene.materialOf(f.triangle);
  orientations[orientation] += w * Vec3d(n);
  side->normalSum += w * Vec3d(n);
  side->centroidSum += w * Vec3d(f.centroid);
  side->weight += w;
  side->area += f.area;
  if (f.backSide) side->backArea += f.area;
  // A textured piece takes its textures' mean over it (at its centroid, over its size).
  Color rho = m.rho, ke = m.emission;
  if (m.rhoTexture || m.emissionTexture) {
    const Vec2 b = scene.barycentricOf(f.triangle, f.centroid);
    const float size = std::sqrt(std::max(f.area, 0.0f));
    rho = scene.reflectanceAt(f.triangle, b, size);
    ke = scene.emissionAt(f.triangle, b, size);
  }
  // Reflectance and emission are means over the covered part.
  const double c = pieceCoverage(scene, f);
  side->coveredArea += double(f.area) * c;
  side->coveredWeight += w * c;
  side->rhoArea += w * c * Vec3d(rho);
  side->keArea += w * c * Vec3d(ke);
  const double emitted = w * luminance(ke);
  if (emitted > side->emitterWeight) {
    side->emitterWeight = emitted;
    side->emitter = scene.faceOf(f.triangle).material;
  }
  return side->id;
}

// The grid's surfaces by content, so that sides made of the same share one.
using SurfaceKey = std::tuple<std::array<float, 6>, uint32_t, bool, uint32_t>;

uint32_t internSurface(VoxelGrid& grid, std::map<SurfaceKey, uint32_t>& index,
                       const VoxelSurface& s) {
  const VoxelMaterial& m = s.material;
  const SurfaceKey key{{m.rho.r, m.rho.g, m.rho.b, m.emission.r, m.emission.g, m.emission.b},
                       s.object,
                       s.backSide,
                       s.emitter};
  auto [it, inserted] = index.emplace(key, uint32_t(grid.surfaces.size()));
  if (inserted) grid.surfaces.push_back(s);
  return it->second;
}

void appendSide(VoxelGrid& grid, std::map<SurfaceKey, uint32_t>& surfaceIndex, const Side& side,
                bool sharesPrevious) {
  grid.orientation.push_back(
      {PackedNormal::pack(Vec3(glm::normalize(side.normalSum))), sharesPrevious});
  grid.centroid.push_back(grid.pack(side.centroidSum / side.weight));
  const float faces = float(side.coveredArea / (double(grid.voxelSize) * grid.voxelSize));
  grid.faceArea.push_back(toHalf(faces));
  const VoxelMaterial m{Color(side.rhoArea / side.coveredWeight),
                        Color(side.keArea / side.coveredWeight)};
  grid.surface.push_back(internSurface(
      grid, surfaceIndex, {m, side.object, side.backArea > 0.5 * side.area, side.emitter}));
}

// The sides a cell's grid entries are, in their order: those at least half covered (the sweeps
// take a side as opaque, and leave one less covered out), by orientation.
void keepEntrySides(std::vector<Side>& sides) {
  std::erase_if(sides, [](const Side& s) {
    return !(s.coveredWeight > 0.0) || !(s.coveredArea >= 0.5 * s.area);
  });
  std::stable_sort(sides.begin(), sides.end(),
                   [](const Side& a, const Side& b) { return a.orientation < b.orientation; });
}

// Calls f(cell key, sides) for each cell of the fragments (sorted by cell): its fragments
// clustered into sides, those of its entries in their order.
template <typename F>
void forEachCellsSides(const Scene& scene, const std::vector<Fragment>& fragments, F&& f) {
  std::vector<Side> sides;
  std::vector<Vec3d> orientations;
  for (size_t i = 0; i < fragments.size();) {
    const uint64_t key = fragments[i].cellKey;
    sides.clear();
    orientations.clear();
    for (; i < fragments.size() && fragments[i].cellKey == key; ++i)
      addToSides(scene, fragments[i], orientations, sides);
    keepEntrySides(sides);
    if (!sides.empty()) f(key, sides);
  }
}

// Sizes the grid's arrays for the cells, rows and sides the fragments make, counted first: grown
// by doubling, they would hold up to twice their size (an address-space limit counts all of it)
// and copy themselves again to shrink.
void reserveEntries(const Scene& scene, const std::vector<Fragment>& fragments, VoxelGrid& grid) {
  size_t cells = 0, rows = 0, entries = 0;
  int lastX = -1, lastY = -1;
  forEachCellsSides(scene, fragments, [&](uint64_t key, const std::vector<Side>& sides) {
    const IVec3 c = keyCell(key);
    if (c.x != lastX || c.y != lastY) ++rows, lastX = c.x, lastY = c.y;
    ++cells;
    entries += sides.size();
  });
  grid.cellZ.reserve(cells);
  grid.cellEntryBegin.reserve(cells + 1);
  grid.rowY.reserve(rows);
  grid.rowCellBegin.reserve(rows + 1);
  grid.orientation.reserve(entries);
  grid.centroid.reserve(entries);
  grid.faceArea.reserve(entries);
  grid.surface.reserve(entries);
}

// Fills the grid's cells, rows, slabs and entries from fragments sorted by cell.
void buildEntries(const Scene& scene, const std::vector<Fragment>& fragments, VoxelGrid& grid) {
  reserveEntries(scene, fragments, grid);
  std::map<SurfaceKey, uint32_t> surfaceIndex;
  grid.slabRowBegin.assign(size_t(grid.dims.x) + 1, 0);
  int lastX = -1, lastY = -1;
  forEachCellsSides(scene, fragments, [&](uint64_t key, const std::vector<Side>& sides) {
    const IVec3 c = keyCell(key);
    if (c.x != lastX || c.y != lastY) {
      grid.rowY.push_back(int16_t(c.y));
      grid.rowCellBegin.push_back(uint32_t(grid.cellZ.size()));
      for (int x = lastX + 1; x <= c.x; ++x) grid.slabRowBegin[x] = uint32_t(grid.rowY.size() - 1);
      lastX = c.x;
      lastY = c.y;
    }
    grid.cellZ.push_back(int16_t(c.z));
    grid.cellEntryBegin.push_back(uint32_t(grid.orientation.size()));
    for (size_t k = 0; k < sides.size(); ++k)
      appendSide(grid, surfaceIndex, sides[k],
                 k > 0 && sides[k].orientation == sides[k - 1].orientation);
  });
  for (int x = lastX + 1; x <= grid.dims.x; ++x) grid.slabRowBegin[x] = uint32_t(grid.rowY.size());
  grid.rowCellBegin.push_back(uint32_t(grid.cellZ.size()));
  grid.cellEntryBegin.push_back(uint32_t(grid.orientation.size()));
}

// Every triangle's pieces in the grid's voxels, sorted by cell, and within a cell by triangle,
// its front before its back. `progress` hears 0.25 and 0.5 (it may be empty).
std::vector<Fragment> sortedFragments(const Scene& scene, const VoxelGrid& grid,
                                      const ProgressCallback& progress) {
  // Each triangle's fragments are counted first, then made again straight into their place in
  // one array, in triangle order (deterministic): clipping twice (0.6 s at 2M voxels) is cheaper
  // than holding them twice. Gathered from per-block vectors, they took 64 B a fragment at the
  // peak: 151 MB before the grid was built for a 2M-voxel room, 77 MB this way.
  const size_t triangles = scene.triangles.size();
  auto twoSided = [&](size_t t) { return scene.materialOf(uint32_t(t)).twoSided; };
  std::vector<size_t> firstFragment(triangles + 1, 0);
  tbb::enumerable_thread_specific<std::vector<Fragment>> scratch;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, triangles, 64), [&](const auto& r) {
    std::vector<Fragment>& pieces = scratch.local();
    for (size_t t = r.begin(); t != r.end(); ++t) {
      pieces.clear();
      fragmentTriangle(scene, grid, uint32_t(t), twoSided(t), pieces);
      firstFragment[t + 1] = pieces.size();
    }
  });
  scratch.clear();
  for (size_t t = 0; t < triangles; ++t) firstFragment[t + 1] += firstFragment[t];
  if (progress && !progress(0.25)) throw Cancelled();
  requireMemory(double(firstFragment[triangles]) * sizeof(Fragment), scene.name,
                fmt::format("the {} pieces of the surfaces in voxels of {:g}",
                            firstFragment[triangles], grid.voxelSize),
                "use a larger voxel size or fewer voxels");
  std::vector<Fragment> fragments(firstFragment[triangles]);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, triangles, 64), [&](const auto& r) {
    for (size_t t = r.begin(); t != r.end(); ++t) {
      FragmentSpan place{fragments.data() + firstFragment[t]};
      fragmentTriangle(scene, grid, uint32_t(t), twoSided(t), place);
    }
  });
  releaseMemory(firstFragment);
  if (progress && !progress(0.5)) throw Cancelled();
  // By cell, and within a cell by triangle, its front before its back (one piece of each per
  // cell): a total order, sorted in place and in parallel, where a stable sort would hold a
  // second copy of the fragments.
  tbb::parallel_sort(fragments.begin(), fragments.end(), [](const Fragment& a, const Fragment& b) {
    return std::tie(a.cellKey, a.triangle, a.backSide) <
           std::tie(b.cellKey, b.triangle, b.backSide);
  });
  return fragments;
}

// A planar piece of area A with unit normal n covers about A (|nx| + |ny| + |nz|) / s^2 voxels
// (the sum of its projections on the three axis planes); this is the sum of those areas.
double projectedArea(const Scene& scene) {
  double covered = 0.0;
  for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
    const Vec3 n = glm::abs(scene.triangleNormal(t));
    covered += scene.triangleArea(t) * (n.x + n.y + n.z);
  }
  return covered;
}

// Voxelizing holds at most about this much per voxel at its peak (the fragments, 32 B each, and
// the grid): 64-71 B measured with the process's own at 1M and 3M voxels of room:16, whose
// surfaces are one-sided; a two-sided surface makes two fragments and two sides a voxel.
constexpr double kVoxelizeBytesPerVoxel = 140.0;

}  // namespace

float voxelSizeForCount(const Scene& scene, size_t targetVoxels) {
  return float(std::sqrt(projectedArea(scene) / double(std::max<size_t>(targetVoxels, 1))));
}

double expectedVoxelCount(const Scene& scene, float voxelSize) {
  return projectedArea(scene) / (double(voxelSize) * double(voxelSize));
}

void forEachSidesPieces(const Scene& scene, const VoxelGrid& grid, size_t firstEntry,
                        size_t lastEntry, const SidePiecesVisitor& visit) {
  if (firstEntry >= lastEntry) return;
  const std::vector<Fragment> fragments = sortedFragments(scene, grid, {});
  auto cellOf = [&](size_t entry) {
    return uint32_t(
        std::upper_bound(grid.cellEntryBegin.begin(), grid.cellEntryBegin.end(), uint32_t(entry)) -
        grid.cellEntryBegin.begin() - 1);
  };
  std::atomic<bool> stopped = false;
  tbb::parallel_for(
      tbb::blocked_range<uint32_t>(cellOf(firstEntry), cellOf(lastEntry - 1) + 1, 16),
      [&](const auto& r) {
        std::vector<Side> sides;
        std::vector<Vec3d> orientations;
        std::vector<uint32_t> sideOf, entryOf;
        std::vector<SidePiece> pieces;
        for (uint32_t cell = r.begin(); cell != r.end() && !stopped; ++cell) {
          const IVec3 c = grid.cellCoordinates(cell);
          const uint64_t key = cellKey(c.x, c.y, c.z);
          const auto first =
              std::lower_bound(fragments.begin(), fragments.end(), key,
                               [](const Fragment& f, uint64_t k) { return f.cellKey < k; });
          const auto last =
              std::upper_bound(first, fragments.end(), key,
                               [](uint64_t k, const Fragment& f) { return k < f.cellKey; });
          sides.clear();
          orientations.clear();
          sideOf.clear();
          for (auto f = first; f != last; ++f)
            sideOf.push_back(addToSides(scene, *f, orientations, sides));
          entryOf.assign(sides.size(), UINT32_MAX);
          keepEntrySides(sides);
          assert(sides.size() == grid.cellEntryBegin[cell + 1] - grid.cellEntryBegin[cell]);
          for (size_t k = 0; k < sides.size(); ++k) entryOf[sides[k].id] = uint32_t(k);
          for (size_t k = 0; k < sides.size(); ++k) {
            const size_t entry = grid.cellEntryBegin[cell] + k;
            if (entry < firstEntry || entry >= lastEntry) continue;
            pieces.clear();
            for (size_t i = 0; i < sideOf.size(); ++i) {
              if (entryOf[sideOf[i]] != k) continue;
              const Fragment& f = first[ptrdiff_t(i)];
              const double covered = std::max(double(f.area), 1e-12) * pieceCoverage(scene, f);
              if (covered > 0.0) pieces.push_back({f.centroid, fragmentNormal(scene, f), covered});
            }
            if (!visit(entry, pieces)) stopped = true;
          }
        }
      });
}

VoxelGrid voxelizeScene(const Scene& scene, const VoxelizerSettings& settings,
                        const ProgressCallback& progress) {
  if (scene.triangles.empty()) throw InputError(scene.name, "no triangles to voxelize");
  VoxelGrid grid;
  grid.voxelSize = settings.voxelSize > 0.0f ? settings.voxelSize
                                             : voxelSizeForCount(scene, settings.targetVoxels);
  Bounds b;
  for (const UVec3& t : scene.triangles)
    for (int k = 0; k < 3; ++k) b.extend(scene.positions[t[k]]);
  // The scene's lowest planes fall on voxel centres, not on voxel faces.
  grid.origin = b.min - 0.5f * grid.voxelSize;
  const Vec3 cells = glm::floor((b.max - grid.origin) / grid.voxelSize) + 1.0f;
  if (glm::any(glm::greaterThan(cells, Vec3(32767.0f))))
    throw InputError(scene.name,
                     fmt::format("voxel size {:g} gives a {:g} x {:g} x {:g} grid (at most "
                                 "32767 per axis)",
                                 grid.voxelSize, cells.x, cells.y, cells.z));
  grid.dims = IVec3(cells);
  grid.pointStep = VoxelGrid::pointStepFor(grid.dims, grid.voxelSize);
  // Refused before the fragments are made, rather than killed for memory while making them.
  const double expected = settings.voxelSize > 0.0f ? expectedVoxelCount(scene, grid.voxelSize)
                                                    : double(settings.targetVoxels);
  requireMemory(
      expected * kVoxelizeBytesPerVoxel, scene.name,
      fmt::format("voxel size {:g} gives about {:.0f} voxels, which", grid.voxelSize, expected),
      "use a larger voxel size or fewer voxels");

  std::vector<Fragment> fragments = sortedFragments(scene, grid, progress);
  buildEntries(scene, fragments, grid);
  releaseMemory(fragments);
  if (progress && !progress(1.0)) throw Cancelled();
  return grid;
}

}  // namespace rad
