// "atrium:N": a generated interior of the kind that real scenes are (the Sponza atrium's kind):
// round columns, arches, thin railings on two galleries and a barrel vault, many small faces next
// to large ones, lit by two lanterns (point lights) and a spot that lights the vault from below.
// N sets the tessellation of the curved parts, so the triangle count grows about linearly with N
// (atrium:1 has 3.0k triangles, atrium:180 about 250k) while the geometry stays the same.
// Textured ("atrium-textured:N"), its floor is tiled and its walls and vault are ashlar
// (procedural textures, planar texture coordinates), at the same mean reflectances.
// Units: metres; y up; the nave runs along z.

#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/scene_builder.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "scene/builtin/builtin_scenes.h"
#include "scene/builtin/builtin_shapes.h"
#include "scene/builtin/stone_textures.h"

namespace rad {

namespace {

constexpr int kMaxDetail = 2000;
constexpr float kPi = std::numbers::pi_v<float>;

constexpr float kWidth = 14.0f, kLength = 24.0f;  // the hall
constexpr float kWallTop = 8.0f;                  // where the vault springs
constexpr float kAisle = 3.25f;                   // gallery depth from each long wall
constexpr float kSlabBottom = 4.2f, kSlabTop = 4.5f;
constexpr float kColumnRadius = 0.35f, kColumnX = 3.0f;
constexpr float kArchSpring = 2.4f, kArchHalfThickness = 0.25f;
constexpr int kBays = 6;  // columns per side, 4 m apart
constexpr float kBay = 4.0f;
constexpr float kGap = 1e-3f;  // between a part and the wall it abuts

struct Materials {
  uint32_t stone, plaster, marble, vault, slab, iron;
};

struct Objects {
  uint32_t floor, walls, aisleCeilings, vault, columns, arches, galleries, railings;
};

// A cylinder's side from y0 to y1 around the vertical axis at (x, z), facing out.
void addColumn(SceneBuilder& b, float x, float z, float y0, float y1, int segments,
               uint32_t material, uint32_t object) {
  for (int k = 0; k < segments; ++k) {
    const float a0 = 2.0f * kPi * float(k) / float(segments);
    const float a1 = 2.0f * kPi * float(k + 1) / float(segments);
    const Vec3 p0(x + kColumnRadius * std::cos(a0), 0.0f, z + kColumnRadius * std::sin(a0));
    const Vec3 p1(x + kColumnRadius * std::cos(a1), 0.0f, z + kColumnRadius * std::sin(a1));
    addQuad(b, Vec3(p0.x, y0, p0.z), Vec3(p0.x, y1, p0.z), Vec3(p1.x, y1, p1.z),
            Vec3(p1.x, y0, p1.z), material, object);
  }
}

// A semicircular arch between columns, in the plane x = centreX, spanning z0..z1: its curved
// underside (the intrados, facing the arch's centre) and both faces of the wall between the
// arc and the gallery slab above, as vertical strips.
void addArch(SceneBuilder& b, float centreX, float z0, float z1, int segments, uint32_t material,
             uint32_t object) {
  const float radius = 0.5f * (z1 - z0), zc = 0.5f * (z0 + z1);
  const float xa = centreX - kArchHalfThickness, xb = centreX + kArchHalfThickness;
  auto arc = [&](int k) {  // from z0 over the crown to z1
    const float a = kPi * (1.0f - float(k) / float(segments));
    return Vec3(0.0f, kArchSpring + radius * std::sin(a), zc + radius * std::cos(a));
  };
  for (int k = 0; k < segments; ++k) {
    const Vec3 p = arc(k), q = arc(k + 1);
    // The intrados faces down and in: from p to q along z, then across x.
    addQuad(b, Vec3(xa, p.y, p.z), Vec3(xb, p.y, p.z), Vec3(xb, q.y, q.z), Vec3(xa, q.y, q.z),
            material, object);
    // The spandrel strips above the arc, facing -x and +x.
    addQuad(b, Vec3(xa, p.y, p.z), Vec3(xa, q.y, q.z), Vec3(xa, kSlabBottom, q.z),
            Vec3(xa, kSlabBottom, p.z), material, object);
    addQuad(b, Vec3(xb, p.y, p.z), Vec3(xb, kSlabBottom, p.z), Vec3(xb, kSlabBottom, q.z),
            Vec3(xb, q.y, q.z), material, object);
  }
  // Its ends, where it meets the columns (wider than the arch is thick, not wide enough to hide
  // the wall's inside).
  addQuad(b, Vec3(xa, kArchSpring, z0), Vec3(xa, kSlabBottom, z0), Vec3(xb, kSlabBottom, z0),
          Vec3(xb, kArchSpring, z0), material, object);
  addQuad(b, Vec3(xa, kArchSpring, z1), Vec3(xb, kArchSpring, z1), Vec3(xb, kSlabBottom, z1),
          Vec3(xa, kSlabBottom, z1), material, object);
}

// Thin square bars every 0.3 m along the gallery's edge at x, and a rail on top.
void addRailing(SceneBuilder& b, float x, uint32_t material, uint32_t object) {
  const float bar = 0.02f, height = 1.0f;
  for (float z = 0.3f; z < kLength - 0.2f; z += 0.3f)
    addBox(b, Vec3(x - bar / 2, kSlabTop, z - bar / 2),
           Vec3(x + bar / 2, kSlabTop + height, z + bar / 2), material, object, BoxSide::Outside,
           false);
  addBox(b, Vec3(x - 0.03f, kSlabTop + height, kGap),
         Vec3(x + 0.03f, kSlabTop + height + 0.05f, kLength - kGap), material, object,
         BoxSide::Outside);
}

// The vault's arc across the nave at parameter k of `segments` (x from one gallery to the other).
Vec3 vaultPoint(int k, int segments) {
  const float radius = 0.5f * (kWidth - 2.0f * kAisle);
  const float a = kPi * float(k) / float(segments);
  return Vec3(0.5f * kWidth + radius * std::cos(a), kWallTop + radius * std::sin(a), 0.0f);
}

// The hall's shell, facing in: floor, long walls, the aisles' flat ceilings, the barrel vault (in
// 2 m sections along the nave) and the two end walls, each a rectangle with the vault's half
// disc on top (one concave polygon).
void addShell(SceneBuilder& b, int vaultSegments, const Materials& m, const Objects& o) {
  addQuad(b, Vec3(0, 0, 0), Vec3(0, 0, kLength), Vec3(kWidth, 0, kLength), Vec3(kWidth, 0, 0),
          m.stone, o.floor);
  addQuad(b, Vec3(0, 0, 0), Vec3(0, kWallTop, 0), Vec3(0, kWallTop, kLength), Vec3(0, 0, kLength),
          m.plaster, o.walls);
  addQuad(b, Vec3(kWidth, 0, 0), Vec3(kWidth, 0, kLength), Vec3(kWidth, kWallTop, kLength),
          Vec3(kWidth, kWallTop, 0), m.plaster, o.walls);
  for (float x0 : {0.0f, kWidth - kAisle})
    addQuad(b, Vec3(x0, kWallTop, 0), Vec3(x0 + kAisle, kWallTop, 0),
            Vec3(x0 + kAisle, kWallTop, kLength), Vec3(x0, kWallTop, kLength), m.plaster,
            o.aisleCeilings);
  constexpr float kSection = 2.0f;
  for (float z = 0.0f; z < kLength - 1e-3f; z += kSection)
    for (int k = 0; k < vaultSegments; ++k) {
      const Vec3 p = vaultPoint(k, vaultSegments), q = vaultPoint(k + 1, vaultSegments);
      addQuad(b, Vec3(p.x, p.y, z), Vec3(p.x, p.y, z + kSection), Vec3(q.x, q.y, z + kSection),
              Vec3(q.x, q.y, z), m.vault, o.vault);
    }
  const std::string& where = b.scene().name;
  for (float z : {0.0f, kLength}) {
    std::vector<uint32_t> corners{b.addVertex(Vec3(0, 0, z), where),
                                  b.addVertex(Vec3(kWidth, 0, z), where),
                                  b.addVertex(Vec3(kWidth, kWallTop, z), where)};
    for (int k = 0; k <= vaultSegments; ++k)
      corners.push_back(b.addVertex(vaultPoint(k, vaultSegments) + Vec3(0, 0, z), where));
    corners.push_back(b.addVertex(Vec3(0, kWallTop, z), where));
    if (z > 0.0f) std::reverse(corners.begin(), corners.end());  // the far wall faces -z
    b.addPolygon(corners, m.plaster, o.walls, where);
  }
}

std::vector<Light> lanternsAndUplight() {
  std::vector<Light> lights;
  for (float z : {8.0f, 16.0f}) {
    Light lantern;
    lantern.type = LightType::Point;
    lantern.position = Vec3(0.5f * kWidth, 2.6f, z);
    lantern.intensity = Color(60.0f, 52.0f, 40.0f);  // W/sr: warm
    lights.push_back(lantern);
  }
  Light uplight;
  uplight.type = LightType::Spot;
  uplight.position = Vec3(0.5f * kWidth, 0.3f, 3.0f);
  uplight.direction = glm::normalize(Vec3(0.0f, 1.0f, 0.6f));
  uplight.intensity = Color(150.0f, 160.0f, 180.0f);
  uplight.innerAngleDeg = 20.0f;
  uplight.outerAngleDeg = 30.0f;
  lights.push_back(uplight);
  return lights;
}

// The materials; textured, the floor's, the walls' and the vault's under their textures.
Materials addMaterials(SceneBuilder& b, bool textured) {
  Material stone{"stone", Color(0.50f, 0.46f, 0.40f)};
  Material plaster{"plaster", Color(0.72f, 0.68f, 0.60f)};
  Material vault{"vault", Color(0.75f, 0.72f, 0.66f)};
  if (textured) {
    applyTexture(stone, makeFloorTiles(512, 4));
    const std::shared_ptr<const Texture> ashlar = makeAshlar(512, 8);
    applyTexture(plaster, ashlar);
    applyTexture(vault, ashlar);
  }
  return {b.addMaterial(stone),
          b.addMaterial(plaster),
          b.addMaterial({"marble", Color(0.65f, 0.64f, 0.62f)}),
          b.addMaterial(vault),
          b.addMaterial({"gallery", Color(0.55f, 0.50f, 0.45f)}),
          b.addMaterial({"iron", Color(0.25f, 0.24f, 0.22f)})};
}

}  // namespace

Scene makeAtrium(int n, bool textured) {
  const std::string name = fmt::format("{}:{}", textured ? "atrium-textured" : "atrium", n);
  if (n < 1 || n > kMaxDetail)
    throw InputError(name, fmt::format("N = {} out of range [1, {}]", n, kMaxDetail));
  SceneBuilder b(name);
  const Materials m = addMaterials(b, textured);
  const Objects o{b.addObject("floor"),     b.addObject("walls"),   b.addObject("aisle_ceilings"),
                  b.addObject("vault"),     b.addObject("columns"), b.addObject("arches"),
                  b.addObject("galleries"), b.addObject("railings")};
  const int columnSegments = 12 * n, archSegments = 8 * n, vaultSegments = 24 * n;

  addShell(b, vaultSegments, m, o);
  for (float x : {kColumnX, kWidth - kColumnX}) {
    for (int i = 0; i < kBays; ++i) {
      const float z = 0.5f * kBay + kBay * float(i);
      addColumn(b, x, z, 0.0f, kSlabBottom, columnSegments, m.marble, o.columns);
      if (i + 1 < kBays)
        addArch(b, x, z + kColumnRadius, z + kBay - kColumnRadius, archSegments, m.marble,
                o.arches);
    }
    // The gallery slab from the long wall to just past the columns, and its railing. Kept a
    // millimetre off the walls: a face on a wall's plane facing the other way hides the wall from
    // rays that meet both at one distance.
    const bool west = x < 0.5f * kWidth;
    const float x0 = west ? kGap : kWidth - kAisle, x1 = west ? kAisle : kWidth - kGap;
    addBox(b, Vec3(x0, kSlabBottom, kGap), Vec3(x1, kSlabTop, kLength - kGap), m.slab, o.galleries,
           BoxSide::Outside);
    addRailing(b, west ? kAisle - 0.1f : kWidth - kAisle + 0.1f, m.iron, o.railings);
  }

  if (textured) {
    mapPlanar(b, m.stone, 2.0f);    // 0.5 m tiles
    mapPlanar(b, m.plaster, 2.4f);  // 0.3 m courses of 0.6 m blocks
    mapPlanar(b, m.vault, 2.4f);
  }
  Scene& s = b.scene();
  s.lights = lanternsAndUplight();
  Camera camera;
  camera.eye = Vec3(0.5f * kWidth, 1.7f, 0.6f);
  camera.target = Vec3(0.5f * kWidth, 4.0f, 0.8f * kLength);
  camera.fovDeg = 70.0f;
  s.camera = camera;
  s.unit = *lengthUnitNamed("m");
  return b.build();
}

}  // namespace rad
