// Where sensors come from: the scene file's "sensors" (points and calculation grids) and a CSV of
// points, with the errors a user gets for a bad one.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <radiosity/error.h>
#include <radiosity/scene_loader.h>
#include <radiosity/sensors.h>

#include "scene_summary.h"

namespace rad {
namespace {

using testing::HasSubstr;

// A floor of 2 x 2 and the sensors given.
std::string sceneWithSensors(const std::filesystem::path& dir, const std::string& sensors) {
  test::writeFile(dir / "floor.obj", "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nf 1 4 3 2\n");
  return test::writeFile(dir / "scene.json", R"({"geometry": [{"file": "floor.obj"}],
    "lights": [{"type": "point", "position": [0, 1, 0], "intensity": [1, 1, 1]}],
    "sensors": )" + sensors + "}");
}

// A grid's points are the centres of its nu x nv cells (EN 12464-1's calculation grid), facing
// u x v's way unless a normal is given; a point is itself.
TEST(SensorInput, AGridIsTheCentresOfItsCells) {
  const auto dir = test::scratchDir("sensors");
  const Scene scene = loadScene(sceneWithSensors(dir, R"([
      {"name": "desk", "position": [0.1, 0.75, 0.2], "normal": [0, 2, 0]},
      {"name": "plane", "grid": {"origin": [-1, 0.8, 1], "u": [2, 0, 0], "v": [0, 0, -1],
                                 "nu": 4, "nv": 2}}])"));
  ASSERT_EQ(scene.sensors.size(), 2u);
  EXPECT_EQ(scene.sensors[0].name, "desk");
  ASSERT_EQ(scene.sensors[0].points.size(), 1u);
  EXPECT_EQ(scene.sensors[0].points[0].normal, Vec3(0, 1, 0));
  const SensorSet& plane = scene.sensors[1];
  ASSERT_EQ(plane.points.size(), 8u);
  EXPECT_NEAR(plane.points[0].position.x, -0.75f, 1e-6f);  // -1 + 2 x 0.5 / 4
  EXPECT_NEAR(plane.points[0].position.z, 0.75f, 1e-6f);   // 1 - 0.5 / 2
  EXPECT_NEAR(plane.points[7].position.x, 0.75f, 1e-6f);
  EXPECT_NEAR(plane.points[7].position.z, 0.25f, 1e-6f);
  EXPECT_NEAR(plane.points[3].position.y, 0.8f, 1e-6f);
  // u x v = (2, 0, 0) x (0, 0, -1) = (0, 2, 0): up.
  EXPECT_EQ(plane.points[5].normal, Vec3(0, 1, 0));
}

TEST(SensorInput, ABadSensorIsNamedByItsPath) {
  const auto dir = test::scratchDir("sensors");
  auto error = [&](const std::string& sensors) {
    return test::errorOf([&] { loadScene(sceneWithSensors(dir, sensors)); });
  };
  EXPECT_THAT(error(R"([{"position": [0, 1, 0], "normal": [0, 0, 0]}])"),
              HasSubstr("/sensors/0/normal: expected a non-zero vector"));
  EXPECT_THAT(error(R"([{"position": [0, 1, 0]}])"), HasSubstr("missing key \"normal\""));
  EXPECT_THAT(error(R"([{"normal": [0, 1, 0]}])"), HasSubstr("either \"position\""));
  EXPECT_THAT(error(R"([{"grid": {"origin": [0, 0, 0], "u": [1, 0, 0], "v": [2, 0, 0],
                         "nu": 2, "nv": 2}}])"),
              HasSubstr("not parallel"));
  EXPECT_THAT(error(R"([{"grid": {"origin": [0, 0, 0], "u": [1, 0, 0], "v": [0, 0, 1],
                         "nu": 0, "nv": 2}}])"),
              HasSubstr("/sensors/0/grid/nu"));
  EXPECT_THAT(error(R"([{"grid": {"origin": [0, 0, 0], "u": [1, 0, 0], "v": [0, 0, 1],
                         "nu": 2000, "nv": 2000}}])"),
              HasSubstr("at most 1000000 a grid"));
  EXPECT_THAT(error(R"([{"name": "a", "position": [0, 1, 0], "normal": [0, 1, 0]},
                        {"name": "a", "position": [0, 1, 0], "normal": [0, 1, 0]}])"),
              HasSubstr("/sensors/1/name: 'a' names another sensor too"));
  EXPECT_THAT(error(R"({"desk": 1})"), HasSubstr("/sensors: expected an array"));
}

// Rows of one name form a set, in the order the names first appear; rows without one are a set
// named after the file; a header row and comments are skipped; normals are made unit.
TEST(SensorInput, ACsvRowIsAPoint) {
  const auto dir = test::scratchDir("sensors");
  const std::string path = test::writeFile(dir / "points.csv",
                                           "x,y,z,nx,ny,nz,name\n"
                                           "# the desks\n"
                                           "0,0.75,0,0,1,0,desk\r\n"
                                           "1, 0.75, 0, 0, 3, 0, \"wall\"\n"
                                           "\n"
                                           "2,0.75,0,0,1,0,desk\n"
                                           "3,0,0,0,0,1\n");
  const std::vector<SensorSet> sets = readSensorCsv(path);
  ASSERT_EQ(sets.size(), 3u);
  EXPECT_EQ(sets[0].name, "desk");
  EXPECT_EQ(sets[0].points.size(), 2u);
  EXPECT_EQ(sets[0].points[1].position, Vec3(2.0f, 0.75f, 0.0f));
  EXPECT_EQ(sets[1].name, "wall");
  EXPECT_EQ(sets[1].points[0].normal, Vec3(0, 1, 0));
  EXPECT_EQ(sets[2].name, "points");
  EXPECT_EQ(sets[2].points[0].normal, Vec3(0, 0, 1));
}

TEST(SensorInput, ABadCsvRowIsNamedByItsLine) {
  const auto dir = test::scratchDir("sensors");
  auto error = [&](const std::string& text) {
    const std::string path = test::writeFile(dir / "bad.csv", text);
    return test::errorOf([&] { readSensorCsv(path); });
  };
  EXPECT_THAT(error("0,0,0,0,1,0\n0,0,0,0,1\n"), HasSubstr("bad.csv:2: expected x,y,z,nx,ny,nz"));
  EXPECT_THAT(error("0,0,0,0,0,0\n"), HasSubstr("bad.csv:1: the normal"));
  EXPECT_THAT(error("0,nan,0,0,1,0\n"), HasSubstr("bad.csv:1: column 2 (y)"));
  EXPECT_THAT(error("x,y,z\n"), HasSubstr("no sensor rows"));
  EXPECT_THAT(test::errorOf([&] { readSensorCsv((dir / "missing.csv").string()); }),
              HasSubstr("missing.csv"));
}

}  // namespace
}  // namespace rad
