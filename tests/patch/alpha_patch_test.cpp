// The patch method with surfaces that are not opaque (Material, Patch::coverage): a black Blend
// sheet of alpha 0.3 between an emitting square and a floor passes 0.7 of the floor's light, and
// a furnace holding a partly covered sheet keeps B = E / (1 - rho) everywhere (reciprocity and
// closure weigh patches by their covered areas; docs/references.md 3.2 for the furnace).
#include <gtest/gtest.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/scene_builder.h>

#include <cstdio>
#include <glm/gtc/constants.hpp>
#include <optional>
#include <string>

#include "render/test_scenes.h"

namespace rad {
namespace {

TEST(AlphaPatch, BlendSheetPassesOneMinusAlphaOfTheLight) {
  const double open =
      test::objectNamed(PatchRadiosity(test::lampOverFloor({}), test::uncachedPatchSettings(300)),
                        "floor")
          .meanIrradiance.g;
  const double through =
      test::objectNamed(PatchRadiosity(test::lampOverFloor(0.3f), test::uncachedPatchSettings(300)),
                        "floor")
          .meanIrradiance.g;
  ASSERT_GT(open, 0.0);
  // The emitter's exact columns, one visibility ray for each of 16 points a patch pair (tens of
  // thousands of rays over the floor): the share within 1%.
  EXPECT_NEAR(through / open, 0.7, 0.01);
  std::printf("blend sheet 0.3: the floor gets %.4f of its light\n", through / open);
}

// The unit furnace (every face emits Ke = 1 and reflects rho = 0.5) holding a two-sided sheet at
// x = 0.5 of the same material, Blend alpha 0.4.
Scene furnaceWithSheet() {
  SceneBuilder b("furnace with a sheet");
  Material wall{"wall", Color(0.5f), Color(1.0f)};
  const uint32_t id = b.addMaterial(wall);
  test::addInwardCube(b, [&](int) { return id; });
  Material sheet = wall;
  sheet.name = "sheet";
  sheet.twoSided = true;
  sheet.alphaMode = AlphaMode::Blend;
  sheet.alpha = 0.4f;
  test::addQuadFacing(b, test::axisSquare(Vec3(0.5f), 0, 0.8f), Vec3(1, 0, 0), b.addMaterial(sheet),
                      b.addObject("sheet"));
  return b.build();
}

TEST(AlphaPatch, FurnaceWithAPartlyCoveredSheetKeepsEOverOneMinusRho) {
  const Scene scene = furnaceWithSheet();
  const PatchRadiosity solution(scene, test::uncachedPatchSettings(1500));
  const double expected = glm::pi<double>() * 1.0 / (1.0 - 0.5);
  for (const ObjectRadiometry& o : solution.objectRadiometry()) {
    SCOPED_TRACE(o.name);
    // The rows' noise at 256 rays, averaged with their columns: 1% on an object's mean.
    EXPECT_NEAR(o.meanRadiosity.g, expected, 0.01 * expected);
    std::printf("furnace with a sheet: %s B / expected %.4f\n", o.name.c_str(),
                o.meanRadiosity.g / expected);
  }
}

}  // namespace
}  // namespace rad
