// The sun placed by date, time and place (scene/sun_position.h) and read from scene files, and
// directional lights in scene files. References: the noon elevation at the June solstice is
// 90 - latitude + the obliquity of the ecliptic (23.4359 degrees in 2026: 23.4393 at J2000.0 less
// 46.8 arc seconds a century, the IAU 1976 rate), and the sun stands due south at noon north of
// the tropic.
#include <gtest/gtest.h>
#include <radiosity/error.h>
#include <radiosity/scene_loader.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "scene/sun_position.h"
#include "scene_summary.h"

namespace rad {
namespace {

UtcTime timeOf(const std::string& text) {
  UtcTime t;
  std::string why;
  EXPECT_TRUE(parseIsoTime(text, t, why)) << text << ": " << why;
  return t;
}

TEST(SunPosition, NoonAtTheJuneSolsticeStandsAtNinetyLessLatitudePlusTheObliquity) {
  for (const double latitude : {40.0, 51.5, 30.0}) {
    // The highest elevation of 21 June 2026 at longitude 0, searched minute by minute.
    SunPosition highest;
    for (int minute = 11 * 60; minute < 13 * 60; ++minute) {
      UtcTime t = timeOf("2026-06-21T00:00:00Z");
      t.julianDay += minute / 1440.0;
      const SunPosition s = sunPosition(t, latitude, 0.0);
      if (s.elevationDeg > highest.elevationDeg) highest = s;
    }
    const double geometric = 90.0 - latitude + 23.4359;
    const double refraction = 58.1 / std::tan(geometric * M_PI / 180.0) / 3600.0;  // < 0.01 deg
    EXPECT_NEAR(highest.elevationDeg, geometric + refraction, 0.01) << "latitude " << latitude;
    EXPECT_NEAR(highest.azimuthDeg, 180.0, 0.5) << "latitude " << latitude;
  }
}

TEST(SunPosition, MorningSunIsInTheEastAndEveningSunInTheWest) {
  const SunPosition morning = sunPosition(timeOf("2026-03-20T07:00:00+01:00"), 48.0, 11.0);
  const SunPosition evening = sunPosition(timeOf("2026-03-20T17:00:00+01:00"), 48.0, 11.0);
  EXPECT_GT(morning.azimuthDeg, 60.0);
  EXPECT_LT(morning.azimuthDeg, 120.0);
  EXPECT_GT(evening.azimuthDeg, 240.0);
  EXPECT_LT(evening.azimuthDeg, 300.0);
  // Near the equinox the sun rises and sets close to 6 and 18 local solar time: low then.
  EXPECT_LT(morning.elevationDeg, 15.0);
  EXPECT_LT(evening.elevationDeg, 15.0);
  // Midnight: below the horizon.
  EXPECT_LT(sunPosition(timeOf("2026-03-20T00:00:00+01:00"), 48.0, 11.0).elevationDeg, -30.0);
}

TEST(SunPosition, OffsetsNameTheSameMoment) {
  EXPECT_DOUBLE_EQ(timeOf("2026-06-21T14:00:00+02:00").julianDay,
                   timeOf("2026-06-21T12:00:00Z").julianDay);
  EXPECT_DOUBLE_EQ(timeOf("2026-06-21T07:30:00-04:30").julianDay,
                   timeOf("2026-06-21T12:00:00Z").julianDay);
  // J2000.0 is JD 2451545.0: 1 January 2000 at 12:00 UTC (Meeus).
  EXPECT_DOUBLE_EQ(timeOf("2000-01-01T12:00:00Z").julianDay, 2451545.0);
  UtcTime t;
  std::string why;
  for (const char* bad : {"2026-06-21T12:00:00", "2026-13-01T12:00:00Z", "2026-02-30T12:00Z",
                          "21/06/2026 12:00", "2026-06-21T25:00:00Z", ""}) {
    EXPECT_FALSE(parseIsoTime(bad, t, why)) << bad;
    EXPECT_FALSE(why.empty()) << bad;
  }
}

TEST(SunPosition, DirectionFollowsTheScenesNorthAndUp) {
  // Due south at 30 degrees, north along -z, up +y: east is +x, so toward the sun is +z and up.
  const Vec3 to = towardSun({30.0, 180.0}, Vec3(0, 1, 0), Vec3(0, 0, -1));
  EXPECT_NEAR(to.y, 0.5f, 1e-6f);
  EXPECT_NEAR(to.z, std::sqrt(3.0f) / 2.0f, 1e-6f);
  const Vec3 east = towardSun({0.0, 90.0}, Vec3(0, 1, 0), Vec3(0, 0, -1));
  EXPECT_NEAR(east.x, 1.0f, 1e-6f);
}

class SceneFileSun : public ::testing::Test {
 protected:
  // A scene file of the small glTF and `lights`, in `unit` ("": none given).
  std::string write(const std::string& lights, const std::string& unit = "m") {
    const auto dir = test::scratchDir("sun_scene");
    const std::string unitKey = unit.empty() ? "" : R"("unit": ")" + unit + R"(", )";
    return test::writeFile(dir / "sun.json",
                           "{" + unitKey + R"("geometry": [{"file": ")" + test::kData +
                               R"(small/small.gltf"}], "lights": )" + lights + "}");
  }
};

TEST_F(SceneFileSun, DirectionalLightIsReadWithItsIrradiance) {
  const Scene s = loadScene(
      write(R"([{"type": "directional", "direction": [0, -2, 0], "irradiance": [3, 2, 1]}])"));
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, LightType::Directional);
  EXPECT_NEAR(s.lights[0].direction.y, -1.0f, 1e-6f);
  EXPECT_EQ(s.lights[0].intensity, Color(3, 2, 1));
}

TEST_F(SceneFileSun, SunIsPlacedByDateAndPlaceWithClearSkyLightInTheScenesUnit) {
  const std::string sun = R"([{"type": "sun", "latitude": 40, "longitude": 0,
      "datetime": "2026-06-21T12:02:00Z", "north": [0, 0, -1]}])";
  const Scene metres = loadScene(write(sun));
  ASSERT_EQ(metres.lights.size(), 1u);
  const Light& l = metres.lights[0];
  EXPECT_EQ(l.type, LightType::Directional);
  // Near noon: from the south (+z here) at about 73.4 degrees, travelling down and north.
  const double elevation = std::asin(-l.direction.y) * 180.0 / M_PI;
  EXPECT_NEAR(elevation, 73.44, 0.05);
  EXPECT_LT(l.direction.z, 0.0f);
  EXPECT_NEAR(l.direction.x, 0.0f, 0.01f);
  // 127,500 lx exp(-0.21 / sin 73.44) = 104,200 lx at 179 lm/W: 582 W/m^2.
  const double lux = 127500.0 * std::exp(-0.21 / std::sin(elevation * M_PI / 180.0));
  EXPECT_NEAR(l.intensity.g, lux / 179.0, 1e-3 * lux / 179.0);
  // The same light in millimetres: per square millimetre.
  const Scene mm = loadScene(write(sun, "mm"));
  EXPECT_NEAR(mm.lights[0].intensity.g, 1e-6 * lux / 179.0, 1e-9 * lux / 179.0);
}

TEST_F(SceneFileSun, SunAtNightLightsNothingAndSaysSo) {
  const Scene s = loadScene(write(R"([{"type": "sun", "latitude": 40, "longitude": 0,
      "datetime": "2026-06-21T00:00:00Z", "north": [0, 0, -1], "illuminance_lux": 1000}])"));
  EXPECT_EQ(s.lights.at(0).intensity, Color(0.0f));
  ASSERT_FALSE(s.warnings.empty());
  EXPECT_NE(s.warnings.back().find("below the horizon"), std::string::npos) << s.warnings.back();
}

TEST_F(SceneFileSun, BadSunsAreErrorsNamingTheKey) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"([{"type": "sun", "latitude": 95, "longitude": 0, "datetime": "2026-06-21T12:00:00Z",
           "north": [0, 0, -1]}])",
       "/lights/0/latitude"},
      {R"([{"type": "sun", "latitude": 40, "longitude": 0, "datetime": "2026-06-21T12:00:00",
           "north": [0, 0, -1]}])",
       "/lights/0/datetime"},
      {R"([{"type": "sun", "latitude": 40, "longitude": 0, "datetime": "2026-06-21T12:00:00Z",
           "north": [0, 1, 0]}])",
       "/lights/0/north"},
      {R"([{"type": "directional", "direction": [0, -1, 0]}])", "irradiance"},
  };
  for (const auto& [lights, where] : cases) {
    try {
      loadScene(write(lights));
      ADD_FAILURE() << "loaded " << lights;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << e.what();
    }
  }
  try {  // lux per square metre needs the scene's unit
    loadScene(write(R"([{"type": "sun", "latitude": 40, "longitude": 0,
        "datetime": "2026-06-21T12:00:00Z", "north": [0, 0, -1]}])",
                    ""));
    ADD_FAILURE() << "a sun in a scene of unknown unit loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unit"), std::string::npos) << e.what();
  }
}

// Photometric keys at 179 lm/W (docs/references.md 4.4): 179 cd is 1 W/sr; a point light's
// 4 pi 179 lm is 1 W/sr; a spot's lumens spread over its profile, whose solid angle (2 pi times the
// integral of the smoothstep falloff over cos theta) is integrated here by a 100,000-step midpoint
// rule; 1,790 lx is 10 W/m^2, 1e-5 W/mm^2.
TEST_F(SceneFileSun, PhotometricKeysConvertAt179LumensPerWatt) {
  const Scene s = loadScene(write(R"([
      {"type": "point", "position": [0, 2, 0], "intensity_cd": 179},
      {"type": "point", "position": [0, 2, 0], "flux_lm": 2249.38033},
      {"type": "spot", "position": [0, 2, 0], "direction": [0, -1, 0], "inner_angle_deg": 20,
       "outer_angle_deg": 30, "flux_lm": [179, 358, 537]},
      {"type": "directional", "direction": [0, -1, 0], "illuminance_lux": 1790}])",
                                  "mm"));
  ASSERT_EQ(s.lights.size(), 4u);
  EXPECT_NEAR(s.lights[0].intensity.g, 1.0f, 1e-6f);
  EXPECT_NEAR(s.lights[1].intensity.g, 1.0f, 1e-6f);  // 4 pi x 179 = 2249.38033
  const double cosOuter = std::cos(30.0 * M_PI / 180.0), cosInner = std::cos(20.0 * M_PI / 180.0);
  double omega = 0.0;
  const int steps = 100000;
  for (int k = 0; k < steps; ++k) {
    const double c = cosOuter + (1.0 - cosOuter) * (k + 0.5) / steps;
    const double t = std::clamp((c - cosOuter) / (cosInner - cosOuter), 0.0, 1.0);
    omega += t * t * (3.0 - 2.0 * t) * (1.0 - cosOuter) / steps;
  }
  omega *= 2.0 * M_PI;
  EXPECT_NEAR(s.lights[2].intensity.r, 1.0 / omega, 1e-4 / omega);
  EXPECT_NEAR(s.lights[2].intensity.b, 3.0 / omega, 3e-4 / omega);
  EXPECT_NEAR(s.lights[3].intensity.g, 1e-5f, 1e-11f);

  for (const auto& [lights, why] : std::vector<std::pair<std::string, std::string>>{
           {R"([{"type": "point", "position": [0, 2, 0], "intensity": [1, 1, 1],
               "intensity_cd": 179}])",
            "give one"},
           {R"([{"type": "point", "position": [0, 2, 0]}])", "intensity_cd"},
           {R"([{"type": "point", "position": [0, 2, 0], "flux_lm": -5}])", "flux_lm"},
           // 1e30 cd is 5.6e27 W/sr, beyond the 1e18 a scene file's light may hold
           {R"([{"type": "point", "position": [0, 2, 0], "intensity_cd": 1e30}])", "below"}}) {
    try {
      loadScene(write(lights));
      ADD_FAILURE() << "loaded " << lights;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace rad
