// The scene file's "sky" and "up" (docs/ARCHITECTURE.md, "Scene file"): a sky becomes a light of
// its own group, standing on the scene's up; what is missing or out of range is an error naming
// its key.
#include <gtest/gtest.h>
#include <radiosity/error.h>
#include <radiosity/image.h>
#include <radiosity/scene_loader.h>

#include <string>
#include <utility>
#include <vector>

#include "scene_summary.h"

namespace rad {
namespace {

// A scene file of the small glTF with `rest` (JSON members after the geometry, or nothing).
Scene loadWith(const std::string& rest) {
  const auto dir = test::scratchDir("sky_scene");
  return loadScene(test::writeFile(dir / "sky.json", R"({"geometry": [{"file": ")" + test::kData +
                                                         R"(small/small.gltf"}])" + rest + "}"));
}

const char* kSun = R"("lights": [{"type": "directional", "direction": [0, -1, -1],
    "irradiance": [1, 1, 1]}])";

TEST(SceneFileSky, SkiesAreLightsOfTheirOwnGroupOnTheScenesUp) {
  const Scene uniform = loadWith(R"(, "sky": {"type": "uniform", "radiance": [3, 2, 1]})");
  ASSERT_EQ(uniform.lights.size(), 1u);
  const Light& sky = uniform.lights[0];
  EXPECT_EQ(sky.type, LightType::Sky);
  EXPECT_EQ(sky.sky.model, SkyModel::Uniform);
  EXPECT_EQ(sky.intensity, Color(3, 2, 1));
  EXPECT_EQ(sky.group, "sky");
  EXPECT_EQ(sky.sky.up, Vec3(0, 1, 0));

  const Scene overcast = loadWith(
      R"(, "up": [0, 0, 2], "sky": {"type": "cie-overcast", "zenith_radiance": [1, 1, 1],
          "group": "daylight"})");
  EXPECT_EQ(overcast.lights.at(0).sky.model, SkyModel::CieOvercast);
  EXPECT_EQ(overcast.lights.at(0).sky.up, Vec3(0, 0, 1));
  EXPECT_EQ(overcast.lights.at(0).group, "daylight");

  // A clear sky stands about the scene's sun: toward it is against the way its light travels.
  const Scene clear = loadWith(std::string(", ") + kSun +
                               R"(, "sky": {"type": "cie-clear", "zenith_radiance": [1, 1, 1]})");
  ASSERT_EQ(clear.lights.size(), 2u);
  const Vec3 toward = clear.lights[1].sky.towardSun;
  EXPECT_NEAR(toward.y, std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(toward.z, std::sqrt(0.5f), 1e-6f);
}

// One up for the scene: a sun's own "up" gives it where the scene has none, and must agree.
TEST(SceneFileSky, ASunsUpIsTheScenes) {
  const std::string sun = R"("lights": [{"type": "sun", "latitude": 40, "longitude": 0,
      "datetime": "2026-06-21T12:00:00Z", "north": [0, 1, 0], "up": [0, 0, 1],
      "irradiance": [1, 1, 1]}])";
  const Scene s = loadWith(", " + sun + R"(, "sky": {"type": "uniform", "radiance": [1, 1, 1]})");
  EXPECT_EQ(s.lights.at(1).sky.up, Vec3(0, 0, 1));
  try {
    loadWith(R"(, "up": [0, 1, 0], )" + sun);
    ADD_FAILURE() << "a sun's up against the scene's loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/lights/0/up"), std::string::npos) << e.what();
  }
}

// An environment map is read from its EXR, turned about up: 90 degrees turns its middle column
// from -z to -x (right-handed about +y).
TEST(SceneFileSky, AnEnvironmentIsReadFromItsMapAndTurned) {
  const auto dir = test::scratchDir("sky_map");  // beside the scene's own, which loadWith empties
  Image map(8, 4);
  map.at(0, 0) = Color(1.0f, 2.0f, 3.0f);
  writeImage((dir / "sky.exr").string(), map, {0.0f, ExrPixelType::Float});
  const Scene s = loadWith(R"(, "sky": {"type": "environment", "file": ")" +
                           (dir / "sky.exr").string() + R"(", "rotation_deg": 90, "scale": 2})");
  const Light& sky = s.lights.at(0);
  EXPECT_EQ(sky.sky.model, SkyModel::Environment);
  ASSERT_TRUE(sky.sky.map);
  EXPECT_EQ(sky.sky.map->at(0, 0), Color(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(sky.intensity, Color(2.0f));
  EXPECT_NEAR(sky.sky.forward.x, -1.0f, 1e-6f);
  EXPECT_NEAR(sky.sky.forward.z, 0.0f, 1e-6f);

  map.at(1, 1) = Color(-1.0f);
  writeImage((dir / "negative.exr").string(), map, {0.0f, ExrPixelType::Float});
  try {
    loadWith(R"(, "sky": {"type": "environment", "file": ")" + (dir / "negative.exr").string() +
             R"("})");
    ADD_FAILURE() << "a negative radiance loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/sky/file"), std::string::npos) << e.what();
  }
}

TEST(SceneFileSky, BadSkiesAreErrorsNamingTheKey) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {R"("sky": {"type": "cloudy", "radiance": [1, 1, 1]})",
       {"/sky/type", "unknown sky type 'cloudy'", "cie-overcast"}},
      {R"("sky": {"radiance": [1, 1, 1]})", {"/sky", "missing key \"type\""}},
      {R"("sky": {"type": "uniform"})", {"/sky", "missing key \"radiance\""}},
      {R"("sky": {"type": "cie-overcast", "radiance": [1, 1, 1]})",
       {"/sky/radiance", "unknown key", "zenith_radiance"}},
      {R"("sky": {"type": "uniform", "radiance": [1, -1, 1]})", {"/sky/radiance", ">= 0"}},
      {R"("sky": {"type": "uniform", "radiance": [1, 1e300, 1]})", {"/sky/radiance/1"}},
      {R"("sky": {"type": "uniform", "radiance": "bright"})", {"/sky/radiance", "3 numbers"}},
      {R"("sky": [1, 1, 1])", {"/sky", "expected an object"}},
      {R"("sky": {"type": "cie-clear", "zenith_radiance": [1, 1, 1]})",
       {"/sky/type", "needs a \"sun\""}},
      {R"("up": [0, 0, 0], "sky": {"type": "uniform", "radiance": [1, 1, 1]})",
       {"/up", "zero length"}},
      {R"("sky": {"type": "environment"})", {"/sky", "missing key \"file\""}},
      {R"("sky": {"type": "environment", "file": "sky.png"})", {"/sky/file", ".exr"}},
      {R"("sky": {"type": "environment", "file": "none.exr"})", {"none.exr"}},
      {R"("sky": {"type": "environment", "file": "a.exr", "radiance": [1, 1, 1]})",
       {"/sky/radiance", "unknown key"}},
  };
  for (const auto& [rest, expected] : cases) {
    try {
      loadWith(", " + rest);
      ADD_FAILURE() << "loaded " << rest;
    } catch (const InputError& e) {
      for (const std::string& part : expected)
        EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace rad
