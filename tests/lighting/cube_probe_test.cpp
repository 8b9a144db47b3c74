// Probes: a cube view of the static scene and a vertex's irradiance from it, three ways, against
// closed forms: a furnace (uniform radiance L all round: E = pi L), a sky linear in z
// (L = 1 + z: E = pi + 2 pi / 3 n_z, the cosine-weighted hemisphere integral), and a coloured
// wall the normal faces.
#include "probes/cube_probe.h"

#include <gtest/gtest.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/scene_builder.h>
#include <radiosity/scene_loader.h>
#include <radiosity/voxel_radiosity.h>

#include <glm/gtc/constants.hpp>

#include "core/rng.h"
#include "render/path_integrator.h"
#include "render/test_scenes.h"

namespace rad {
namespace {

constexpr float kPi = glm::pi<float>();

// What the walls emit, as a solution would show it (rho 0: radiance is emission).
class EmissionOnly : public SurfaceRadiance {
 public:
  explicit EmissionOnly(const Scene& scene) : scene_(scene) {}
  Color radiance(const SurfaceHit& hit) const override {
    return hit.frontFace ? scene_.materialOf(hit.triangle).emission : Color(0.0f);
  }

 private:
  const Scene& scene_;
};

// The unit cube seen from inside, face k emitting `emission(k)` (faces -x, +x, -y, +y, -z, +z).
template <class Emission>
Scene glowingCube(Emission emission) {
  SceneBuilder b("cube");
  std::vector<uint32_t> materials;
  for (int face = 0; face < 6; ++face)
    materials.push_back(
        b.addMaterial({"face" + std::to_string(face), Color(0.0f), emission(face), false}));
  test::addInwardCube(b, [&](int face) { return materials[size_t(face)]; });
  return b.build();
}

const std::vector<Vec3> kNormals = {Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0, -1, 0),
                                    glm::normalize(Vec3(1, 2, 3)),
                                    glm::normalize(Vec3(-0.3f, 0.1f, -1))};

TEST(CubeProbe, TexelsCoverTheSphere) {
  const CubeProbe probe(16);
  double sum = 0.0;
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) sum += 6.0 * probe.solidAngle(i, j);
  EXPECT_NEAR(sum, 4.0 * glm::pi<double>(), 1e-9);
}

TEST(CubeProbe, FurnaceGivesPiLEveryWay) {
  const Color l(0.5f, 1.0f, 2.0f);
  const Scene scene = glowingCube([&](int) { return l; });
  const RayCaster caster(scene);
  CubeProbe probe(16);
  probe.capture(caster, EmissionOnly(scene), Vec3(0.5f, 0.4f, 0.6f));
  for (const Vec3& n : kNormals)
    for (ProbeIrradiance way :
         {ProbeIrradiance::Exact, ProbeIrradiance::Harmonic, ProbeIrradiance::Pattern}) {
      const Color e = probe.irradiance(n, way);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(e[c], kPi * l[c], 0.01f * kPi * l[c]) << int(way);
    }
}

// A sky of radiance 1 + z, filled texel by texel. The exact sum is within its texels' cosine
// error; order-2 harmonics represent it exactly; the published pattern is biased: its four
// texels a ring are not cosine-distributed: 13.3% at worst over these normals at 16 texels a
// face (the pattern is drawn once from a fixed seed, so the number is the same every run).
TEST(CubeProbe, LinearSkyAgainstTheClosedForm) {
  CubeProbe probe(16);
  for (int face = 0; face < 6; ++face)
    for (int j = 0; j < 16; ++j)
      for (int i = 0; i < 16; ++i)
        probe.texel(face, i, j) = Color(1.0f + probe.direction(face, i, j).z);
  probe.project();
  double worstPattern = 0.0;
  for (const Vec3& n : kNormals) {
    const float expected = kPi + 2.0f * kPi / 3.0f * n.z;
    EXPECT_NEAR(probe.exactIrradiance(n).r, expected, 0.01f * expected);
    EXPECT_NEAR(probe.harmonicIrradiance(n).r, expected, 0.01f * expected);
    worstPattern = std::max(worstPattern,
                            double(std::abs(probe.patternIrradiance(n).r - expected) / expected));
  }
  EXPECT_LE(worstPattern, 0.14);
  EXPECT_GE(worstPattern, 0.12);  // the stated bias, not a better or worse one
}

TEST(CubeProbe, AVertexFacingARedWallGetsMoreRed) {
  // +x wall red, the others dim green.
  const Scene scene = glowingCube(
      [](int face) { return face == 1 ? Color(1.0f, 0.0f, 0.0f) : Color(0.0f, 0.2f, 0.0f); });
  const RayCaster caster(scene);
  CubeProbe probe(16);
  probe.capture(caster, EmissionOnly(scene), Vec3(0.5f));
  for (ProbeIrradiance way :
       {ProbeIrradiance::Exact, ProbeIrradiance::Harmonic, ProbeIrradiance::Pattern}) {
    const Color toward = probe.irradiance(Vec3(1, 0, 0), way);
    const Color away = probe.irradiance(Vec3(-1, 0, 0), way);
    EXPECT_GT(toward.r, toward.g) << int(way);
    EXPECT_GT(away.g, away.r) << int(way);
    EXPECT_GT(toward.r, 2.0f * away.r) << int(way);
  }
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

// The probe at the Cornell box's centre, facing up (the lamp above), against the reference path
// tracer's irradiance at that point (200k samples): the exact way within 3% for the patch and
// voxel solutions' views (measured -0.8% and -0.5% with 3 x 3 rays a texel; +2.7% and +3.0%
// with one, the lamp's edge texels aliasing). The harmonics ring around the small bright lamp
// that gives most of this irradiance: +4.4% and +4.7%, bound 6%; they are meant for the smooth
// bounce light, where they are exact (the linear-sky test).
TEST(CubeProbe, CornellCentreMatchesThePathTracer) {
  const Scene scene = loadScene("cornell");
  const RayCaster caster(scene);
  const Bounds b = scene.bounds();
  const Vec3 centre = 0.5f * (b.min + b.max), up(0.0f, 1.0f, 0.0f);
  const PathIntegrator integrator(scene, caster, 64);
  Vec3d sum(0.0);
  constexpr int kSamples = 200000;  // its noise ~0.3%
  for (int s = 0; s < kSamples; ++s) {
    Rng rng(7, uint64_t(s));
    sum += Vec3d(integrator.irradiance(centre, up, rng));
  }
  const Color reference(sum / double(kSamples));
  PatchRadiositySettings patch;
  patch.targetPatches = 3000;
  VoxelRadiositySettings voxel;
  voxel.targetVoxels = 30000;
  voxel.sphereRadius = 12;
  const PatchRadiosity patchSolution(scene, patch);
  const VoxelRadiosity voxelSolution(scene, voxel);
  for (const SurfaceRadiance* solution : {static_cast<const SurfaceRadiance*>(&patchSolution),
                                          static_cast<const SurfaceRadiance*>(&voxelSolution)}) {
    CubeProbe probe(64, 3);
    probe.capture(caster, *solution, centre);
    for (ProbeIrradiance way : {ProbeIrradiance::Exact, ProbeIrradiance::Harmonic}) {
      const Color e = probe.irradiance(up, way);
      const float bound = way == ProbeIrradiance::Exact ? 0.03f : 0.06f;
      EXPECT_NEAR(luminance(e), luminance(reference), bound * luminance(reference)) << int(way);
    }
  }
}

}  // namespace
}  // namespace rad
