// The camera flags of render and animate: --eye, --target, --up and --fov over the scene's camera,
// and --camera to pick one of the cameras its glTF files carry.

#include <gtest/gtest.h>
#include <radiosity/image.h>

#include "cli_run.h"

namespace rad::test {
namespace {

std::vector<std::string> render(const fs::path& out, std::initializer_list<std::string> more) {
  std::vector<std::string> args = {"render",   "cornell", "--method", "pathtrace",
                                   "--spp",    "4",       "--width",  "32",
                                   "--height", "32",      "-o",       out.string()};
  args.insert(args.end(), more);
  return args;
}

TEST(CameraFlags, EyeTargetUpAndFovSetTheView) {
  const fs::path dir = freshDir("camera_flags");
  ASSERT_EQ(run(render(dir / "default.pfm", {})).status, 0);
  // The Cornell box's own camera (its data page), restated: the same picture.
  ASSERT_EQ(run(render(dir / "restated.pfm", {"--eye", "278,273,-800", "--target", "278,273,0",
                                              "--up", "0,2,0", "--fov", "39.3077"}))
                .status,
            0);
  EXPECT_EQ(readBytes((dir / "restated.pfm").string()), readBytes((dir / "default.pfm").string()));
  // From inside the box, looking at the ceiling's light: far brighter than the view from outside.
  ASSERT_EQ(run(render(dir / "up.pfm", {"--eye", "278,100,280", "--target", "278,548,280", "--up",
                                        "0,0,1", "--fov", "30"}))
                .status,
            0);
  auto mean = [](const Image& image) {
    double sum = 0.0;
    for (const Color& c : image.pixels) sum += c.r + c.g + c.b;
    return sum / double(image.pixels.size());
  };
  EXPECT_GT(mean(readImage((dir / "up.pfm").string())),
            3.0 * mean(readImage((dir / "default.pfm").string())));
}

TEST(CameraFlags, AViewThatIsNoViewIsRefused) {
  const fs::path dir = freshDir("camera_flags_bad");
  CliResult r = run(render(dir / "x.pfm", {"--eye", "1,2,3", "--target", "1,2,3"}));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("eye and target coincide"), std::string::npos) << r.err;
  r = run(render(dir / "x.pfm", {"--up", "0,0,5"}));  // the Cornell camera looks along +z
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--up"), std::string::npos) << r.err;
  r = run(render(dir / "x.pfm", {"--eye", "1,2"}));
  EXPECT_EQ(r.status, 2) << r.err;
  r = run(render(dir / "x.pfm", {"--fov", "180"}));
  EXPECT_EQ(r.status, 2) << r.err;
  r = run(render(dir / "x.pfm", {"--camera", "front"}));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("carry no camera"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "x.pfm"));
}

TEST(CameraFlags, CameraPicksOneOfTheGltfCamerasByNameOrIndex) {
  const fs::path dir = freshDir("camera_flags_gltf");
  const std::string data = std::string(RADIOSITY_TEST_DATA_DIR) + "/scene/small/";
  fs::copy_file(data + "small.bin", dir / "small.bin");
  nlohmann::json g = readJson(data + "small.gltf");
  g["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "point"}, {"intensity", 500}}};
  g["cameras"] = {{{"type", "perspective"},
                   {"name", "wide"},
                   {"perspective", {{"yfov", 1.0}, {"aspectRatio", 2.0}, {"znear", 0.1}}}},
                  {{"type", "perspective"},
                   {"name", "square"},
                   {"perspective", {{"yfov", 1.0}, {"aspectRatio", 1.0}, {"znear", 0.1}}}}};
  const size_t n = g["nodes"].size();
  g["nodes"].push_back({{"camera", 0}, {"translation", {2, 1.5, 3.9}}});
  g["nodes"].push_back({{"camera", 1}, {"translation", {2, 1.5, 3.9}}});
  g["nodes"].push_back(
      {{"translation", {2, 2.5, 2}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  for (size_t k = n; k < n + 3; ++k) g["scenes"][0]["nodes"].push_back(k);
  const std::string scene = writeFile(dir / "lit.gltf", g.dump()).string();
  auto size = [&](std::initializer_list<std::string> pick) {
    std::vector<std::string> args = {
        "render", scene,     "--method", "pathtrace", "--spp",
        "1",      "--width", "64",       "-o",        (dir / "x.pfm").string()};
    args.insert(args.end(), pick);
    const CliResult r = run(args);
    EXPECT_EQ(r.status, 0) << r.err;
    const Image image = readImage((dir / "x.pfm").string());
    return std::pair(image.width, image.height);
  };
  // The first camera is the scene's; its aspect ratio gives the height for a width given alone.
  EXPECT_EQ(size({}), std::pair(64, 32));
  EXPECT_EQ(size({"--camera", "square"}), std::pair(64, 64));
  EXPECT_EQ(size({"--camera", "0"}), std::pair(64, 32));
  const CliResult r = run({"render", scene, "--camera", "nope", "-o", (dir / "y.pfm").string()});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("the scene's: wide, square"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace rad::test
