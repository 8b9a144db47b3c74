// The /api/lights body against a directional light (the sun): its direction and irradiance are
// edited like a spot's axis and intensity, a position is refused (it has none: a position would
// be taken and change nothing).
#include "server/light_request.h"

#include <gtest/gtest.h>
#include <radiosity/error.h>
#include <radiosity/light_groups.h>
#include <radiosity/scene_builder.h>

#include <nlohmann/json.hpp>

namespace rad {
namespace {

Scene sunlitTriangle() {
  SceneBuilder b("sunlit");
  const uint32_t m = b.addMaterial({"grey", Color(0.5f), Color(0.0f), false});
  const uint32_t o = b.addObject("floor");
  const uint32_t corners[] = {b.addVertex(Vec3(0, 0, 0), "test"),
                              b.addVertex(Vec3(0, 0, -1), "test"),
                              b.addVertex(Vec3(1, 0, 0), "test")};
  b.addPolygon(corners, m, o, "test");
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = Vec3(0, -1, 0);
  sun.intensity = Color(500.0f);
  b.scene().lights.push_back(sun);
  return b.build();
}

TEST(LightRequest, ADirectionalLightTurnsAndDimsButHasNoPosition) {
  const Scene scene = sunlitTriangle();
  const std::vector<LightGroup> groups = lightGroupsOf(scene, scene.lights);
  const LightRequestRules rules{scene, groups, "", ""};
  const LightState now{scene.lights, std::vector<Color>(groups.size(), Color(1.0f))};
  const LightState turned = lightStateAfter(
      nlohmann::json::parse(
          R"({"lights": [{"id": 0, "direction": [0, -3, 4], "intensity": [2, 2, 2]}]})"),
      now, rules);
  EXPECT_NEAR(turned.lights[0].direction.y, -0.6f, 1e-6f);
  EXPECT_NEAR(turned.lights[0].direction.z, 0.8f, 1e-6f);
  EXPECT_EQ(turned.lights[0].intensity, Color(2.0f));
  try {
    lightStateAfter(nlohmann::json::parse(R"({"lights": [{"id": 0, "position": [1, 2, 3]}]})"), now,
                    rules);
    ADD_FAILURE() << "a position was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/lights/0/position"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no position"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rad
