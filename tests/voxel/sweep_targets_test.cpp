// The voxel sweep on every instruction set its pass was compiled for that the processor runs
// (Highway's targets: AVX-512, AVX2, SSE4, SSSE3, one lane at a time): the same solve as on the
// widest, bit for bit where both fuse multiply-adds, within 1e-4 elsewhere (9e-6 measured).
#include <gtest/gtest.h>
#include <hwy/targets.h>
#include <radiosity/scene.h>
#include <radiosity/scene_loader.h>
#include <radiosity/voxel_radiosity.h>

#include <span>
#include <vector>

#include "voxel/sweep_pass.h"

namespace rad {
namespace {

// The per-object mean radiosity of a small Cornell solve (10k voxels, R = 6: under a second) on
// `target`.
std::vector<Color> cornellMeansOn(int64_t target) {
  const Scene scene = loadScene("cornell");
  hwy::SetSupportedTargetsForTest(target);
  VoxelRadiositySettings settings;
  settings.targetVoxels = 10000;
  settings.sphereRadius = 6;
  const VoxelRadiosity solution(scene, settings);
  hwy::SetSupportedTargetsForTest(0);
  std::vector<Color> means;
  for (const ObjectRadiometry& o : solution.objectRadiometry()) means.push_back(o.meanRadiosity);
  return means;
}

// Whether code for `target` fuses a * b + c as the widest's does: AVX2 and wider on x86 (in a
// build for x86-64-v3 the others fuse too, the whole library being built for FMA, but a build with
// no -march leaves SSE4 and below unfused); every target of a processor with FMA in its base (ARM).
bool fusesAsTheWidest(int64_t target, int64_t widest) {
#if HWY_ARCH_X86
  const int64_t fused = HWY_AVX3_DL | HWY_AVX3 | HWY_AVX2;
  return (target & fused) != 0 && (widest & fused) != 0;
#else
  (void)target, (void)widest;
  return true;
#endif
}

TEST(SweepTargets, EveryInstructionSetSolvesAsTheWidest) {
  const std::vector<int64_t> targets = sweep::sweepTargets();
  ASSERT_FALSE(targets.empty());
  const std::vector<Color> widest = cornellMeansOn(targets.front());
  for (int64_t target : std::span(targets).subspan(1)) {
    SCOPED_TRACE(hwy::TargetName(target));
    const std::vector<Color> means = cornellMeansOn(target);
    ASSERT_EQ(means.size(), widest.size());
    for (size_t o = 0; o < means.size(); ++o)
      for (int c = 0; c < 3; ++c) {
        if (fusesAsTheWidest(target, targets.front()))
          EXPECT_EQ(means[o][c], widest[o][c]) << "object " << o << " channel " << c;
        else
          EXPECT_NEAR(means[o][c], widest[o][c], 1e-4f * widest[o][c])
              << "object " << o << " channel " << c;
      }
  }
}

}  // namespace
}  // namespace rad
