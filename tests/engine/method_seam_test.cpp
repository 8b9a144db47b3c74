// A method only the suite knows, registered at run time, goes through the same code as the built-in
// ones: its settings join the one table (flags, scene keys, stats), the commands' solve
// (cli::solveSurfaces through the RadiosityEngine) solves it, the pictures' renderer draws it, its
// solutions are saved and loaded through the shared solution file, and the viewer's session serves
// it. The method
// ("facet-direct") lights each scene triangle by the point lights at its centroid, through one
// shadow ray each, without bounces: what it gives is the inverse-square cosine law
// (docs/references.md 3.5), which the tests check it against.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <radiosity/error.h>
#include <radiosity/radiosity_engine.h>
#include <radiosity/radiosity_method.h>
#include <radiosity/run_stats.h>
#include <radiosity/scene_builder.h>
#include <radiosity/solution_file.h>
#include <radiosity/viewer_session.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "console.h"
#include "method_options.h"
#include "picture_options.h"
#include "render/test_scenes.h"
#include "scene/scene_summary.h"
#include "scene/setting_fields.h"
#include "scene/solution_file.h"

namespace rad {
namespace {

constexpr const char* kName = "facet-direct";

struct FacetSettings {
  bool shadows = true;  ///< cast shadow rays (else every light is seen)
};

// Each triangle's irradiance from the lights at its centroid.
class FacetSolution final : public SurfaceSolution {
 public:
  FacetSolution(const Scene& scene, std::vector<Light> lights, std::vector<Color> irradiance)
      : scene_(scene), lights_(std::move(lights)), irradiance_(std::move(irradiance)) {}

  Color radiance(const SurfaceHit& hit) const override {
    if (!hit.frontFace) return Color(0.0f);
    return scene_.emissionAt(hit.triangle, hit.barycentric) +
           scene_.reflectanceAt(hit.triangle, hit.barycentric) * irradiance_[hit.triangle] /
               float(M_PI);
  }
  Color irradiance(const SurfaceHit& hit) const override {
    return hit.frontFace ? irradiance_[hit.triangle] : Color(0.0f);
  }
  std::span<const Light> directLights() const override { return lights_; }
  const Scene& scene() const override { return scene_; }
  size_t elementCount() const override { return irradiance_.size(); }
  SurfaceElement element(size_t t) const override {
    const Material& m = scene_.materialOf(uint32_t(t));
    SurfaceElement e;
    e.object = scene_.faceOf(uint32_t(t)).object;
    e.area = scene_.triangleArea(uint32_t(t));
    e.position = centroid(t);
    e.normal = scene_.triangleNormal(uint32_t(t));
    e.emitted = float(M_PI) * m.emission;
    e.rho = m.rho;
    e.irradiance = irradiance_[t];
    e.radiosity = e.emitted + e.rho * e.irradiance;
    return e;
  }
  LitMesh litMesh() const override {
    LitMesh mesh;
    for (size_t t = 0; t < irradiance_.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        mesh.indices.push_back(uint32_t(mesh.positions.size()));
        mesh.positions.push_back(scene_.positions[scene_.triangles[t][k]]);
        mesh.normals.push_back(scene_.triangleNormal(uint32_t(t)));
        mesh.colors.push_back(element(t).radiosity / float(M_PI));
      }
    return mesh;
  }
  SolveReport report() const override {
    SolveReport r;
    r.summary = fmt::format("{} facets lit at their centroids", irradiance_.size());
    r.rays = irradiance_.size() * lights_.size();
    r.converged = true;
    r.detailsJson = nlohmann::json{{"facets", irradiance_.size()}}.dump();
    return r;
  }
  void save(const std::string& path, const SolverSettings& settings) const override {
    std::string bytes = solutionFileStart(kName, scene_, lights_, settings);
    putArray(bytes, std::span<const Color>(irradiance_));
    writeSolutionFile(path, bytes);
  }
  Vec3 centroid(size_t t) const {
    const UVec3 tri = scene_.triangles[t];
    return (scene_.positions[tri[0]] + scene_.positions[tri[1]] + scene_.positions[tri[2]]) / 3.0f;
  }

 private:
  const Scene& scene_;
  std::vector<Light> lights_;
  std::vector<Color> irradiance_;
};

class FacetModel final : public MethodModel {
 public:
  FacetModel(const Scene& scene, const RayCaster& caster, FacetSettings settings)
      : scene_(scene), caster_(caster), settings_(settings) {}
  std::string solveLabel() const override { return "facets"; }
  std::unique_ptr<SurfaceSolution> solve(std::span<const Light> lights,
                                         const RayCaster* shadowCaster,
                                         const ProgressCallback& /*progress*/) const override {
    const RayCaster& caster = shadowCaster ? *shadowCaster : caster_;
    std::vector<Color> irradiance(scene_.triangles.size(), Color(0.0f));
    for (size_t t = 0; t < irradiance.size(); ++t) {
      const UVec3 tri = scene_.triangles[t];
      const Vec3 p =
          (scene_.positions[tri[0]] + scene_.positions[tri[1]] + scene_.positions[tri[2]]) / 3.0f;
      const Vec3 n = scene_.triangleNormal(uint32_t(t));
      for (const Light& l : lights) {
        const Vec3 toward = l.position - p;
        const float d = glm::length(toward), cosine = glm::dot(n, toward) / d;
        if (cosine <= 0.0f) continue;
        if (settings_.shadows &&
            caster.occluded(Ray{p + 1e-4f * n, toward / d, 0.0f, d * (1.0f - 1e-4f)}))
          continue;
        irradiance[t] += l.intensity * cosine / (d * d);
      }
    }
    return std::make_unique<FacetSolution>(scene_, std::vector<Light>(lights.begin(), lights.end()),
                                           std::move(irradiance));
  }
  std::unique_ptr<SurfaceSolution> load(const std::string& path,
                                        std::span<const Light> lights) const override {
    const SolutionFile file(path);
    file.checkFor(kName, scene_, lights);
    std::vector<Color> irradiance;
    file.readPayload([&](ByteReader r) { irradiance = r.array<Color>(scene_.triangles.size()); });
    return std::make_unique<FacetSolution>(scene_, std::vector<Light>(lights.begin(), lights.end()),
                                           std::move(irradiance));
  }

 private:
  const Scene& scene_;
  const RayCaster& caster_;
  FacetSettings settings_;
};

class FacetMethod final : public RadiosityMethod {
 public:
  std::string name() const override { return kName; }
  std::string settingsGroup() const override { return "Facet method"; }
  MethodCapabilities capabilities() const override {
    MethodCapabilities c;
    c.saveSolution = true;
    return c;
  }
  std::vector<SettingDeclaration> settingDeclarations() const override {
    return {sectionField("facet_shadows", "Facet method", &FacetSettings::shadows,
                         "Cast a shadow ray toward each light")};
  }
  std::unique_ptr<MethodModel> prepare(const Scene& scene, const RayCaster& caster,
                                       const MethodSettings& settings) const override {
    return std::make_unique<FacetModel>(scene, caster, settings.section<FacetSettings>());
  }
};

// The registration: once per test binary.
void registerFacetMethod() {
  static const bool registered = [] {
    registerRadiosityMethod(std::make_unique<FacetMethod>());
    return true;
  }();
  (void)registered;
}

// A 2 x 2 floor (two triangles, their centroids at (-1/3, -1/3) and (1/3, 1/3)) at z = 0 under a
// point light of 2 W/sr at height 1, and a small blocker halfway between the light and the first
// centroid that shadows it.
Scene floorUnderALight(bool blocker) {
  SceneBuilder b("floor under a light");
  const uint32_t grey = b.addMaterial({"grey", Color(0.5f)});
  test::addQuadFacing(b, test::axisSquare(Vec3(0.0f), 2, 2.0f), Vec3(0, 0, 1), grey,
                      b.addObject("floor"));
  if (blocker)
    test::addQuadFacing(b, test::axisSquare(Vec3(-1.0f / 6.0f, -1.0f / 6.0f, 0.5f), 2, 0.1f),
                        Vec3(0, 0, 1), grey, b.addObject("blocker"));
  Scene scene = b.build();
  Light light;
  light.position = Vec3(0.0f, 0.0f, 1.0f);
  light.intensity = Color(2.0f);
  scene.lights.push_back(light);
  return scene;
}

// H = I h / d^3 at `p` on the floor under the light at height 1 (docs/references.md 3.5).
float inverseSquareCosine(const Vec3& p) {
  const float d = std::sqrt(p.x * p.x + p.y * p.y + 1.0f);
  return 2.0f * 1.0f / (d * d * d);
}

MethodSettings facetSettings(const Scene& scene, SolverSettings given = {}) {
  given.values["method"] = std::string(kName);
  return resolveMethodSettings(scene.solver, given, scene.name);
}

TEST(MethodSeam, ARegisteredMethodsSettingsJoinTheOneTable) {
  registerFacetMethod();
  const RadiosityMethod& facet = radiosityMethod(kName);
  const SettingDeclaration* shadows = findSolverSetting("facet_shadows");
  ASSERT_NE(shadows, nullptr);
  EXPECT_EQ(shadows->flag(), "--facet-shadows");
  EXPECT_TRUE(shadows->readBy(facet));
  EXPECT_FALSE(shadows->readBy(radiosityMethod("patch")));
  EXPECT_FALSE(findSolverSetting("patch_size")->readBy(facet));
  // The general settings it can use: seed and tolerance (it solves the surfaces), not groups.
  EXPECT_TRUE(findSolverSetting("tolerance")->readBy(facet));
  EXPECT_FALSE(findSolverSetting("light_groups")->readBy(facet));
  // A scene key sets it; the stats report it by name.
  Scene scene = floorUnderALight(false);
  scene.solver.values["facet_shadows"] = false;
  const MethodSettings settings = facetSettings(scene);
  EXPECT_FALSE(settings.section<FacetSettings>().shadows);
  bool reported = false;
  for (const auto& [name, value] : settingsOf(settings)) {
    EXPECT_NE(name, "patch_size");
    if (name == "facet_shadows") reported = !std::get<bool>(value);
  }
  EXPECT_TRUE(reported);
  // A bad value is refused naming the scene's key, as for any method's setting.
  scene.solver.values["facet_shadows"] = int64_t(3);
  EXPECT_THROW(facetSettings(scene), InputError);
  // Capabilities decide where it is offered.
  const std::vector<std::string> solving = methodsWith(&MethodCapabilities::surfaceSolution);
  const std::vector<std::string> relighting = methodsWith(&MethodCapabilities::relight);
  EXPECT_NE(std::find(solving.begin(), solving.end(), kName), solving.end());
  EXPECT_EQ(std::find(relighting.begin(), relighting.end(), kName), relighting.end());
  const std::vector<std::string> solveOffers =
      cli::offeredMethods({&MethodCapabilities::surfaceSolution, "voxel", {}, true});
  EXPECT_EQ(solveOffers.front(), "voxel");
  EXPECT_NE(std::find(solveOffers.begin(), solveOffers.end(), kName), solveOffers.end());
  const std::vector<std::string> animateOffers =
      cli::offeredMethods({&MethodCapabilities::relight, "patch", {}, true});
  EXPECT_EQ(std::find(animateOffers.begin(), animateOffers.end(), kName), animateOffers.end());
}

TEST(MethodSeam, TheCommandsSolveItAndReportItsNumbers) {
  registerFacetMethod();
  const Scene scene = floorUnderALight(true);
  const RadiosityEngine engine(scene, facetSettings(scene));
  std::ostringstream out, err;
  cli::Console console(out, err);
  console.setQuiet(true);
  RunStats stats;
  const std::unique_ptr<SurfaceSolution> solution =
      cli::solveSurfaces(engine, {{}, "", 0.0}, console, {stats, true});
  ASSERT_EQ(solution->elementCount(), scene.triangles.size());
  int lit = 0, shadowed = 0;
  for (size_t t = 0; t < solution->elementCount(); ++t) {
    const SurfaceElement e = solution->element(t);
    if (scene.objects[e.object].name != "floor") continue;
    // The blocker hides the light from one floor triangle's centroid only.
    if (e.irradiance.r == 0.0f) {
      ++shadowed;
      continue;
    }
    ++lit;
    EXPECT_NEAR(e.irradiance.r, inverseSquareCosine(e.position), 1e-5f);
  }
  EXPECT_EQ(lit, 1);
  EXPECT_EQ(shadowed, 1);
  EXPECT_EQ(stats.methodDetails["facets"], scene.triangles.size());
  EXPECT_EQ(stats.converged, std::optional<bool>(true));
  ASSERT_FALSE(stats.objects.empty());  // the per-object means, as for any method
}

TEST(MethodSeam, ThePicturesDrawIt) {
  registerFacetMethod();
  const Scene scene = floorUnderALight(false);
  SolverSettings given;
  given.values["spp"] = int64_t(1);
  const RadiosityEngine engine(scene, facetSettings(scene, given));
  const std::unique_ptr<SurfaceSolution> solution = engine.solve(scene.lights, 0.0);
  // Looking straight down at (0.5, 0.3): a point of the triangle below, which shows
  // rho H / pi with H that of its centroid.
  cli::PictureOptions picture;
  picture.direct = "solution";
  Camera camera;
  camera.eye = Vec3(0.5f, 0.3f, 3.0f);
  camera.target = Vec3(0.5f, 0.3f, 0.0f);
  camera.width = camera.height = 9;
  camera.fovDeg = 1.0f;
  const Image image = picture.render(engine, *solution, camera, 0.0, {});
  uint32_t below = 0;
  const Vec2 b = scene.barycentricOf(0, Vec3(0.5f, 0.3f, 0.0f));
  if (b.x < 0.0f || b.y < 0.0f || b.x + b.y > 1.0f) below = 1;
  const Vec3 c =
      (scene.positions[scene.triangles[below][0]] + scene.positions[scene.triangles[below][1]] +
       scene.positions[scene.triangles[below][2]]) /
      3.0f;
  EXPECT_NEAR(image.at(4, 4).r, 0.5f * inverseSquareCosine(c) / float(M_PI), 1e-5f);
}

TEST(MethodSeam, ItsSolutionsAreSavedAndLoadedThroughTheSharedFile) {
  registerFacetMethod();
  const Scene scene = floorUnderALight(true);
  const RayCaster caster(scene);
  const MethodSettings settings = facetSettings(scene);
  const std::unique_ptr<MethodModel> model =
      radiosityMethod(kName).prepare(scene, caster, settings);
  const std::unique_ptr<SurfaceSolution> solved = model->solve(scene.lights, nullptr, {});
  const std::string path = (test::scratchDir("facet") / "floor.rad").string();
  solved->save(path, cli::solvedWith(settings));
  const SolutionFileInfo info = readSolutionFileInfo(path);
  EXPECT_EQ(info.method, kName);
  EXPECT_EQ(std::get<bool>(info.settings.values.at("facet_shadows")), true);
  const std::unique_ptr<SurfaceSolution> loaded = model->load(path, scene.lights);
  for (size_t t = 0; t < solved->elementCount(); ++t)
    EXPECT_EQ(loaded->element(t).irradiance, solved->element(t).irradiance);
  // Lights other than those it was solved for: refused, naming the file.
  std::vector<Light> moved = scene.lights;
  moved[0].position.z = 2.0f;
  EXPECT_THROW(model->load(path, moved), InputError);
  // The patch method refuses a file of another method.
  EXPECT_THROW(radiosityMethod("patch").prepare(scene, caster, settings)->load(path, scene.lights),
               InputError);
}

TEST(MethodSeam, TheViewerServesItAndRefusesToRelightIt) {
  registerFacetMethod();
  const Scene scene = floorUnderALight(false);
  auto engine = std::make_unique<const RadiosityEngine>(scene, facetSettings(scene));
  std::unique_ptr<SurfaceSolution> solution = engine->solve(scene.lights, 0.0);
  ViewerSession session(std::move(engine), scene.lights, std::move(solution), 0.5f);
  EXPECT_EQ(session.summary()["method"], kName);
  EXPECT_FALSE(session.summary()["relights"].get<bool>());
  const std::string before = session.colors();
  try {
    session.applyLights(nlohmann::json::parse(R"({"lights": [{"id": 0, "position": [0, 0, 2]}]})"));
    ADD_FAILURE() << "a light edit of a method that does not relight was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("serve --method patch"), std::string::npos) << e.what();
  }
  EXPECT_EQ(session.colors(), before);
}

}  // namespace
}  // namespace rad
