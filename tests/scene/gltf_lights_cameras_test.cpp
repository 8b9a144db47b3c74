// The lights and cameras a glTF file carries (how Blender exports them): KHR_lights_punctual point
// and spot lights, perspective cameras, placed by their nodes.

#include <gtest/gtest.h>
#include <radiosity/error.h>
#include <radiosity/scene_loader.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>

#include "scene_summary.h"

namespace rad {
namespace {

using Json = nlohmann::json;

void expectNear(const Vec3& a, const Vec3& b, float tolerance = 1e-5f) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], tolerance) << "component " << k;
}

class GltfLightsAndCameras : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::scratchDir("gltf_lights");
    for (const char* f : {"small.gltf", "small.bin"})
      std::filesystem::copy_file(test::kData + "small/" + f, dir_ / f);
    std::ifstream in(dir_ / "small.gltf");
    gltf_ = Json::parse(in);
    const double eighth = std::numbers::pi / 4;  // half the angle of a -90 degree turn about x
    gltf_["extensions"]["KHR_lights_punctual"]["lights"] = {
        {{"type", "point"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 179.0}},
        {{"type", "spot"},
         {"intensity", 358.0},
         {"spot", {{"innerConeAngle", 0.25}, {"outerConeAngle", 0.5}}}},
        {{"type", "directional"}, {"intensity", 3.0}}};
    gltf_["cameras"] = {
        {{"type", "perspective"},
         {"name", "overview"},
         {"perspective", {{"yfov", 0.9}, {"aspectRatio", 2.0}, {"znear", 0.1}}}},
        {{"type", "perspective"}, {"perspective", {{"yfov", 1.2}, {"znear", 0.1}}}}};
    Json& nodes = gltf_["nodes"];
    const size_t first = nodes.size();
    nodes.push_back({{"camera", 0}, {"translation", {2, 1.5, 3.9}}});
    nodes.push_back({{"camera", 1}, {"translation", {1, 1, 1}}});
    nodes.push_back(
        {{"translation", {2, 2.5, 2}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    nodes.push_back({{"translation", {3, 2.9, 1}},
                     {"rotation", {-std::sin(eighth), 0, 0, std::cos(eighth)}},  // -z to -y
                     {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    nodes.push_back({{"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
    for (size_t n = first; n < nodes.size(); ++n) gltf_["scenes"][0]["nodes"].push_back(n);
  }
  std::string write(const std::string& name, const Json& j) {
    return test::writeFile(dir_ / name, j.dump());
  }
  std::filesystem::path dir_;
  Json gltf_;
};

TEST_F(GltfLightsAndCameras, PointSpotAndDirectionalLightsAreReadInRadiometricUnits) {
  const Scene s = loadScene(write("lit.gltf", gltf_));
  ASSERT_EQ(s.lights.size(), 3u);
  // Candela to W/sr as for IES files: 179 cd of white light is 1 W/sr.
  const Light& point = s.lights[0];
  EXPECT_EQ(point.type, LightType::Point);
  expectNear(point.position, Vec3(2, 2.5, 2));
  expectNear(point.intensity, Vec3(1.0f, 0.5f, 0.25f));
  const Light& spot = s.lights[1];
  EXPECT_EQ(spot.type, LightType::Spot);
  expectNear(spot.position, Vec3(3, 2.9, 1));
  expectNear(spot.direction, Vec3(0, -1, 0));  // the node's -z, turned a quarter about x
  expectNear(spot.intensity, Vec3(2.0f));
  EXPECT_NEAR(spot.innerAngleDeg, 0.25 * 180 / std::numbers::pi, 1e-4);
  EXPECT_NEAR(spot.outerAngleDeg, 0.5 * 180 / std::numbers::pi, 1e-4);
  // Lux to W/m^2 at the same 179 lm/W; glTF lengths are metres, so W per square scene unit.
  const Light& sun = s.lights[2];
  EXPECT_EQ(sun.type, LightType::Directional);
  expectNear(sun.direction, Vec3(0, 0, -1));  // the node's -z
  expectNear(sun.intensity, Vec3(3.0f / 179.0f));
  for (const std::string& w : s.warnings) EXPECT_EQ(w.find("light"), std::string::npos) << w;
}

TEST_F(GltfLightsAndCameras, AnUnknownLightTypeIsAnErrorNamingIt) {
  gltf_["extensions"]["KHR_lights_punctual"]["lights"][2]["type"] = "area";
  try {
    loadScene(write("area.gltf", gltf_));
    FAIL() << "loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("lights/2/type"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'area'"), std::string::npos) << e.what();
  }
}

TEST_F(GltfLightsAndCameras, CamerasAreReadAndTheFirstIsTheScenes) {
  const Scene s = loadScene(write("lit.gltf", gltf_));
  ASSERT_EQ(s.cameras.size(), 2u);
  EXPECT_EQ(s.cameras[0].first, "overview");
  EXPECT_EQ(s.cameras[1].first, "camera1");
  const Camera& c = s.cameras[0].second;
  expectNear(c.eye, Vec3(2, 1.5, 3.9));
  expectNear(glm::normalize(c.target - c.eye), Vec3(0, 0, -1));
  expectNear(c.up, Vec3(0, 1, 0));
  EXPECT_NEAR(c.fovDeg, 0.9 * 180 / std::numbers::pi, 1e-4);
  EXPECT_EQ(c.width, 2 * c.height);  // aspect ratio 2
  ASSERT_TRUE(s.camera);
  expectNear(s.camera->eye, c.eye);
}

TEST_F(GltfLightsAndCameras, ASceneFilesTransformMovesThemAndItsCameraWins) {
  write("lit.gltf", gltf_);
  const std::string scene = test::writeFile(dir_ / "scene.json", R"({
    "geometry": [{"file": "lit.gltf", "transform": {"translate": [10, 0, 0]}}],
    "camera": {"eye": [0, 1, 9], "target": [0, 1, 0]}})");
  const Scene s = loadScene(scene);
  expectNear(s.lights[0].position, Vec3(12, 2.5, 2));
  expectNear(s.cameras[0].second.eye, Vec3(12, 1.5, 3.9));
  expectNear(s.camera->eye, Vec3(0, 1, 9));
}

TEST_F(GltfLightsAndCameras, BadLightsAndCamerasNameTheirPlace) {
  Json bad = gltf_;
  bad["nodes"].back()["extensions"]["KHR_lights_punctual"]["light"] = 7;
  EXPECT_NE(test::errorOf([&] { loadScene(write("a.gltf", bad)); }).find("light 7 does not exist"),
            std::string::npos);
  bad = gltf_;
  bad["extensions"]["KHR_lights_punctual"]["lights"][1]["spot"]["outerConeAngle"] = 2.0;
  EXPECT_NE(test::errorOf([&] { loadScene(write("b.gltf", bad)); }).find("cone angles"),
            std::string::npos);
  bad = gltf_;
  bad["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] = -1.0;
  EXPECT_NE(test::errorOf([&] { loadScene(write("c.gltf", bad)); }).find(">= 0"),
            std::string::npos);
}

}  // namespace
}  // namespace rad
