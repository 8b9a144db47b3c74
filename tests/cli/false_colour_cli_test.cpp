// render --false-colour: a lighting designer's picture from every method, refused before any
// work where it cannot be right.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "cli_run.h"

namespace rad::test {
namespace {

using testing::HasSubstr;

// A PNG's width, from its IHDR chunk (big-endian at byte 16).
uint32_t pngWidth(const std::string& path) {
  const std::string bytes = readBytes(path);
  if (bytes.size() < 24) return 0;
  uint32_t w = 0;
  for (int i = 16; i < 20; ++i) w = (w << 8) | uint8_t(bytes[size_t(i)]);
  return w;
}

TEST(FalseColourCli, EveryMethodDrawsItWithItsLegend) {
  const fs::path dir = freshDir("false_colour");
  for (const std::vector<std::string>& method :
       {std::vector<std::string>{"--method", "patch", "--patches", "400", "--cache-dir", "none"},
        std::vector<std::string>{"--method", "pathtrace", "--spp", "2"}}) {
    const std::string out = (dir / (method[1] + ".png")).string();
    std::vector<std::string> args = {"render",  "cornell", "--false-colour", "lux",
                                     "--width", "64",      "--height",       "64",
                                     "-o",      out,       "--quiet"};
    args.insert(args.end(), method.begin(), method.end());
    const CliResult r = run(args);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_GT(pngWidth(out), 64u) << method[1];  // the legend's strip beside the picture
  }
}

TEST(FalseColourCli, LuxWithoutAUnitOrAnIrradianceItCannotShowAreRefused) {
  const fs::path dir = freshDir("false_colour_refused");
  const std::string obj = std::string(RADIOSITY_TEST_DATA_DIR) + "/scene/cornell/cornell_box.obj";
  const CliResult noUnit =
      run({"render", obj, "--false-colour", "lux", "-o", (dir / "x.png").string()});
  EXPECT_EQ(noUnit.status, 2);
  EXPECT_THAT(noUnit.err, HasSubstr("--false-colour lux: the scene's length unit is not known"));
  const CliResult solutionLight =
      run({"render", "cornell", "--method", "patch", "--direct", "solution", "--false-colour",
           "irradiance", "-o", (dir / "y.png").string()});
  EXPECT_EQ(solutionLight.status, 2);
  EXPECT_THAT(solutionLight.err, HasSubstr("needs --direct per-pixel"));
}

}  // namespace
}  // namespace rad::test
