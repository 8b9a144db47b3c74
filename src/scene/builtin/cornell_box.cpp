// The Cornell box. Geometry: the Cornell "Cornell Box Data" page as written in
// tests/data/scene/cornell/cornell_box.obj (docs/references.md 2.3, 2.4): the ceiling is 8 quads
// around the light's 130 x 105 mm hole, the warped red wall is two triangles, the front is open
// and the blocks have no bottoms. Materials: docs/references.md 2.5.

#include <radiosity/scene_builder.h>

#include <array>
#include <initializer_list>
#include <vector>

#include "scene/builtin/builtin_scenes.h"

namespace rad {

namespace {

// Vertices in mm, numbered from 1 as in cornell_box.obj.
constexpr std::array<std::array<float, 3>, 36> kVertices{{
    {552.8f, 0.0f, 0.0f},     {0.0f, 0.0f, 0.0f},       {0.0f, 0.0f, 559.2f},
    {549.6f, 0.0f, 559.2f},   {0.0f, 548.8f, 0.0f},     {213.0f, 548.8f, 0.0f},
    {213.0f, 548.8f, 227.0f}, {0.0f, 548.8f, 227.0f},   {343.0f, 548.8f, 0.0f},
    {343.0f, 548.8f, 227.0f}, {556.0f, 548.8f, 0.0f},   {556.0f, 548.8f, 227.0f},
    {213.0f, 548.8f, 332.0f}, {0.0f, 548.8f, 332.0f},   {556.0f, 548.8f, 332.0f},
    {343.0f, 548.8f, 332.0f}, {213.0f, 548.8f, 559.2f}, {0.0f, 548.8f, 559.2f},
    {343.0f, 548.8f, 559.2f}, {556.0f, 548.8f, 559.2f}, {130.0f, 165.0f, 65.0f},
    {82.0f, 165.0f, 225.0f},  {240.0f, 165.0f, 272.0f}, {290.0f, 165.0f, 114.0f},
    {290.0f, 0.0f, 114.0f},   {240.0f, 0.0f, 272.0f},   {130.0f, 0.0f, 65.0f},
    {82.0f, 0.0f, 225.0f},    {423.0f, 330.0f, 247.0f}, {265.0f, 330.0f, 296.0f},
    {314.0f, 330.0f, 456.0f}, {472.0f, 330.0f, 406.0f}, {423.0f, 0.0f, 247.0f},
    {472.0f, 0.0f, 406.0f},   {314.0f, 0.0f, 456.0f},   {265.0f, 0.0f, 296.0f},
}};

struct Part {
  const char* name;
  int material;  // index into the materials added below
  std::vector<std::vector<uint32_t>> faces;
};

// Materials (linear sRGB, docs/references.md 2.5): the measured Cornell reflectance spectra times
// CIE D65, integrated against the CIE 1931 2-degree observer, normalised so a perfect white
// reflector is 1, converted with the BT.709 XYZ->RGB matrix for that D65 white.
enum { kWhite, kRed, kGreen, kLight };

const std::vector<Part>& parts() {
  static const std::vector<Part> kParts{
      {"floor", kWhite, {{1, 2, 3, 4}}},
      {"ceiling",
       kWhite,
       {{5, 6, 7, 8},
        {6, 9, 10, 7},
        {9, 11, 12, 10},
        {8, 7, 13, 14},
        {10, 12, 15, 16},
        {14, 13, 17, 18},
        {13, 16, 19, 17},
        {16, 15, 20, 19}}},
      {"back_wall", kWhite, {{4, 3, 18, 20}}},
      {"right_wall_green", kGreen, {{3, 2, 5, 18}}},
      {"left_wall_red", kRed, {{1, 4, 20}, {1, 20, 11}}},
      {"light", kLight, {{10, 16, 13, 7}}},
      {"short_block",
       kWhite,
       {{21, 22, 23, 24}, {25, 24, 23, 26}, {27, 21, 24, 25}, {28, 22, 21, 27}, {26, 23, 22, 28}}},
      {"tall_block",
       kWhite,
       {{29, 30, 31, 32}, {33, 29, 32, 34}, {34, 32, 31, 35}, {35, 31, 30, 36}, {36, 30, 29, 33}}},
  };
  return kParts;
}

}  // namespace

Scene makeCornellBox(bool spot) {
  SceneBuilder builder(spot ? "cornell-spot" : "cornell");
  const std::string where = builder.scene().name;
  for (const auto& v : kVertices) builder.addVertex(Vec3(v[0], v[1], v[2]), where);

  builder.addMaterial({"white", Color(0.7383f, 0.7360f, 0.7387f)});
  builder.addMaterial({"red", Color(0.4939f, 0.0489f, 0.0512f)});
  builder.addMaterial({"green", Color(0.0684f, 0.3985f, 0.0866f)});
  // Ke: the Cornell light spectrum (400: 0, 500: 8, 600: 15.6, 700: 18.4) to linear sRGB, XYZ
  // divided by the CIE Y integral (docs/references.md 2.5); relative units. rho 0.78 as in
  // Mitsuba's cbox (not a Cornell measurement).
  const Color lightKe = spot ? Color(0.0f) : Color(20.7115f, 10.8551f, 2.7708f);
  builder.addMaterial({"light", Color(0.78f), lightKe});

  for (const Part& part : parts()) {
    const uint32_t object = builder.addObject(part.name);
    for (const auto& face : part.faces) {
      std::vector<uint32_t> corners;
      for (uint32_t c : face) corners.push_back(c - 1);
      builder.addPolygon(corners, uint32_t(part.material), object, where);
    }
  }

  if (spot) {
    // Just below the light's centre (x 278, z 279.5), aimed straight down. The axial intensity
    // (W/sr, the same relative units as Ke) gives the floor point below it the irradiance the
    // ceiling light gives there: I / d^2 = pi Ke F with d = 538.8 mm and the point-to-light form
    // factor F = 0.014206958 (docs/references.md 2.6), i.e. I = (268360, 140650, 35901).
    Light light;
    light.type = LightType::Spot;
    light.position = Vec3(278.0f, 538.8f, 279.5f);
    light.direction = Vec3(0.0f, -1.0f, 0.0f);
    light.intensity = Color(268360.0f, 140650.0f, 35901.0f);
    light.innerAngleDeg = 25.0f;
    light.outerAngleDeg = 35.0f;
    builder.scene().lights.push_back(light);
  }

  Camera camera;
  camera.eye = Vec3(278.0f, 273.0f, -800.0f);
  camera.target = Vec3(278.0f, 273.0f, 0.0f);
  camera.up = Vec3(0.0f, 1.0f, 0.0f);
  camera.fovDeg = 39.3077f;  // 2 atan(12.5 / 35): the data page's 25 mm film, 35 mm lens
  camera.width = 512;
  camera.height = 512;
  builder.scene().camera = camera;
  builder.scene().unit = *lengthUnitNamed("mm");
  return builder.build();
}

}  // namespace rad
