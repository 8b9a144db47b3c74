// Sensors from the command line: --sensors, --sensor-output and the stats' "sensors" agree with
// each other, read lux in a scene of known unit, and the methods read the same light.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "cli_run.h"

namespace rad::test {
namespace {

using testing::HasSubstr;

// The rows of a CSV after its header, split at commas.
std::vector<std::vector<std::string>> csvRows(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::vector<std::string> fields;
    std::stringstream s(line);
    for (std::string field; std::getline(s, field, ',');) fields.push_back(field);
    rows.push_back(fields);
  }
  return rows;
}

// Two points of the Cornell box (millimetres): on the floor beside the short block facing up, and
// in the air above the blocks facing the back wall.
fs::path cornellSensors(const fs::path& dir) {
  return writeFile(dir / "desk.csv",
                   "x,y,z,nx,ny,nz,name\n150,0.5,400,0,1,0,floor\n278,400,200,0,0,1,air\n");
}

TEST(SensorsCli, TheCsvAndTheStatsReadTheSameLux) {
  const fs::path dir = freshDir("sensors");
  const std::string out = (dir / "read.csv").string(), stats = (dir / "s.json").string();
  const CliResult r =
      run({"solve", "cornell", "--method", "patch", "--patches", "400", "--cache-dir", "none",
           "--sensors", cornellSensors(dir).string(), "--sensor-output", out, "--stats", stats});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("sensors floor:"));
  const nlohmann::json j = readJson(stats)["sensors"];
  ASSERT_TRUE(j.contains("floor") && j.contains("air"));
  const std::vector<std::vector<std::string>> rows = csvRows(out);
  ASSERT_EQ(rows.size(), 2u);
  for (const auto& row : rows) {
    ASSERT_EQ(row.size(), 12u);
    const nlohmann::json& point = j[row[0]]["points"][0];
    const double lux = std::stod(row[11]);
    // 179 lm/W on Y, from W/mm^2 to W/m^2 (x 1e6).
    const nlohmann::json& h = point["irradiance"];
    const double y =
        0.2126 * h[0].get<double>() + 0.7152 * h[1].get<double>() + 0.0722 * h[2].get<double>();
    EXPECT_NEAR(lux, 179.0 * 1e6 * y, 1e-4 * lux);
    EXPECT_NEAR(point["illuminance_lux"].get<double>(), lux, 1e-4 * lux);
    EXPECT_NEAR(std::stod(row[9]), h[1].get<double>(), 1e-4 * h[1].get<double>());
    EXPECT_NEAR(j[row[0]]["mean_lux"].get<double>(), lux, 1e-4 * lux);
    EXPECT_EQ(j[row[0]]["uniformity"].get<double>(), 1.0);
  }
}

// The path tracer's reading of the same points is within its noise of the patch method's: the
// two share no code beyond the direct light's.
TEST(SensorsCli, ThePathTracerReadsWhatThePatchMethodReads) {
  const fs::path dir = freshDir("sensors_methods");
  const std::string sensors = cornellSensors(dir).string();
  const std::string patch = (dir / "patch.json").string(), traced = (dir / "pt.json").string();
  ASSERT_EQ(run({"solve", "cornell", "--method", "patch", "--patches", "2000", "--cache-dir",
                 "none", "--sensors", sensors, "--stats", patch, "--quiet"})
                .status,
            0);
  ASSERT_EQ(run({"render", "cornell", "-o", (dir / "pt.png").string(), "--width", "8", "--spp", "1",
                 "--object-points", "0", "--sensors", sensors, "--sensor-rays", "8192", "--stats",
                 traced, "--quiet"})
                .status,
            0);
  for (const char* set : {"floor", "air"}) {
    const double a = readJson(patch)["sensors"][set]["mean_lux"].get<double>();
    const double b = readJson(traced)["sensors"][set]["mean_lux"].get<double>();
    EXPECT_NEAR(a, b, 0.03 * b) << set;
  }
}

TEST(SensorsCli, SensorOutputWithoutSensorsIsRefusedBeforeAnyWork) {
  const fs::path dir = freshDir("sensors_refused");
  const CliResult r = run({"solve", "cornell", "--sensor-output", (dir / "x.csv").string()});
  EXPECT_EQ(r.status, 2);
  EXPECT_THAT(r.err, HasSubstr("--sensor-output: no sensors to measure"));
  const CliResult missing = run({"solve", "cornell", "--sensors", (dir / "none.csv").string()});
  EXPECT_EQ(missing.status, 2);
  EXPECT_THAT(missing.err, HasSubstr("none.csv"));
}

}  // namespace
}  // namespace rad::test
