// "room:N": a procedural furnished room for scaling tests. The room holds a grid of N cells,
// each with one piece of furniture (table, box stack or shelf) and one ceiling light panel, so
// the triangle count grows linearly with N while the room's proportions stay alike.
// Units: metres. Every cell's furniture depends only on its index (its own Rng stream), so
// room:N is a prefix of room:N+1.

#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/scene_builder.h>

#include <array>
#include <cmath>

#include "core/rng.h"
#include "scene/builtin/builtin_scenes.h"
#include "scene/builtin/builtin_shapes.h"

namespace rad {

namespace {

constexpr float kCell = 2.0f;    // metres per grid cell
constexpr float kHeight = 2.8f;  // ceiling height
constexpr int kMaxCells = 1000000;

struct Materials {
  uint32_t wall, floor, ceiling, panel, wood, paint, shelf;
};

void addTable(SceneBuilder& b, Vec3 o, Rng& rng, const Materials& m, uint32_t object) {
  const float w = 0.8f + 0.6f * rng.uniform(), d = 0.6f + 0.4f * rng.uniform(), h = 0.75f;
  const float leg = 0.05f, top = 0.04f;
  addBox(b, o + Vec3(-w / 2, h - top, -d / 2), o + Vec3(w / 2, h, d / 2), m.wood, object,
         BoxSide::Outside);
  for (int i = 0; i < 4; ++i) {
    const float x = (i & 1) ? w / 2 - leg : -w / 2, z = (i & 2) ? d / 2 - leg : -d / 2;
    addBox(b, o + Vec3(x, 0, z), o + Vec3(x + leg, h - top, z + leg), m.wood, object,
           BoxSide::Outside, false);
  }
}

void addBoxStack(SceneBuilder& b, Vec3 o, Rng& rng, const Materials& m, uint32_t object) {
  float y = 0.0f;
  for (int i = 0; i < 2; ++i) {
    const float s = (0.5f - 0.15f * float(i)) * (0.8f + 0.4f * rng.uniform());
    addBox(b, o + Vec3(-s / 2, y, -s / 2), o + Vec3(s / 2, y + s, s / 2), m.paint, object,
           BoxSide::Outside, i > 0);
    y += s;
  }
}

void addShelf(SceneBuilder& b, Vec3 o, Rng& rng, const Materials& m, uint32_t object) {
  const float w = 0.8f + 0.4f * rng.uniform(), d = 0.35f, h = 1.8f, t = 0.03f;
  addBox(b, o + Vec3(-w / 2, 0, -d / 2), o + Vec3(-w / 2 + t, h, d / 2), m.shelf, object,
         BoxSide::Outside, false);
  addBox(b, o + Vec3(w / 2 - t, 0, -d / 2), o + Vec3(w / 2, h, d / 2), m.shelf, object,
         BoxSide::Outside, false);
  for (int i = 0; i < 4; ++i) {
    const float y = 0.1f + float(i) * (h - 0.2f) / 3.0f;
    addBox(b, o + Vec3(-w / 2 + t, y, -d / 2), o + Vec3(w / 2 - t, y + t, d / 2), m.shelf, object,
           BoxSide::Outside);
  }
}

}  // namespace

Scene makeRoom(int n) {
  if (n < 1 || n > kMaxCells)
    throw InputError(fmt::format("room:{}", n),
                     fmt::format("N = {} out of range [1, {}]", n, kMaxCells));
  SceneBuilder b(fmt::format("room:{}", n));
  const Materials m{b.addMaterial({"wall", Color(0.70f, 0.70f, 0.66f)}),
                    b.addMaterial({"floor", Color(0.45f, 0.35f, 0.25f)}),
                    b.addMaterial({"ceiling", Color(0.80f, 0.80f, 0.80f)}),
                    b.addMaterial({"light_panel", Color(0.80f), Color(4.0f, 3.8f, 3.4f)}),
                    b.addMaterial({"wood", Color(0.50f, 0.32f, 0.20f)}),
                    b.addMaterial({"paint", Color(0.60f, 0.20f, 0.18f)}),
                    b.addMaterial({"shelf", Color(0.30f, 0.45f, 0.60f)})};
  const int cols = int(std::ceil(std::sqrt(double(n))));
  const int rows = (n + cols - 1) / cols;
  const Vec3 size(float(cols) * kCell, kHeight, float(rows) * kCell);

  // The shell: floor, ceiling and walls as separate objects, all facing into the room.
  const uint32_t shell = b.addObject("walls");
  addBox(b, Vec3(0.0f), size, m.wall, shell, BoxSide::Inside);
  Scene& s = b.scene();
  // Floor and ceiling faces were added 3rd and 4th (-y, +y): give them their own objects.
  const uint32_t floorObject = b.addObject("floor"), ceilingObject = b.addObject("ceiling");
  for (Face& f : s.faces) {
    if (f.normal.y > 0.5f) f.object = floorObject, f.material = m.floor;
    if (f.normal.y < -0.5f) f.object = ceilingObject, f.material = m.ceiling;
  }

  for (int i = 0; i < n; ++i) {
    Rng rng(0x726f6f6dULL, uint64_t(i));
    const Vec3 centre((float(i % cols) + 0.5f) * kCell, 0.0f, (float(i / cols) + 0.5f) * kCell);
    // z's shift is drawn first, the order GCC gave the former one-expression form (unspecified in
    // C++), so that the rooms stay as they were whatever the compiler.
    const float dz = (rng.uniform() - 0.5f) * 0.4f;
    const float dx = (rng.uniform() - 0.5f) * 0.4f;
    const Vec3 offset(dx, 0.0f, dz);
    const int kind = i % 3;
    const char* names[] = {"table", "boxes", "shelf"};
    const uint32_t object = b.addObject(fmt::format("{}_{}", names[kind], i));
    if (kind == 0)
      addTable(b, centre + offset, rng, m, object);
    else if (kind == 1)
      addBoxStack(b, centre + offset, rng, m, object);
    else
      addShelf(b, centre + offset, rng, m, object);

    // A 0.6 m square panel facing down, 1 cm below the ceiling (so it does not share the
    // ceiling's plane).
    const uint32_t panel = b.addObject(fmt::format("light_panel_{}", i));
    const float y = kHeight - 0.01f, h = 0.3f;
    std::array<uint32_t, 4> c{b.addVertex(Vec3(centre.x - h, y, centre.z - h), s.name),
                              b.addVertex(Vec3(centre.x + h, y, centre.z - h), s.name),
                              b.addVertex(Vec3(centre.x + h, y, centre.z + h), s.name),
                              b.addVertex(Vec3(centre.x - h, y, centre.z + h), s.name)};
    b.addPolygon(c, m.panel, panel, s.name);
  }

  Camera camera;
  camera.eye = Vec3(size.x * 0.5f, 1.6f, 0.05f * size.z + 0.1f);
  camera.target = Vec3(size.x * 0.5f, 0.8f, size.z * 0.6f);
  camera.fovDeg = 60.0f;
  s.camera = camera;
  s.unit = *lengthUnitNamed("m");
  return b.build();
}

}  // namespace rad
