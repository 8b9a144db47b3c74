// The path tracer as a RadiosityMethod: no surface solution; pictures and per-object means of
// the scene as it is, the reference the other methods are judged against.
#include "render/path_tracer_method.h"

#include <fmt/format.h>
#include <radiosity/path_tracer.h>

#include "scene/setting_fields.h"

namespace rad {

namespace {

const std::string kGroup = "Path tracer";

PathTracerSettings pathTracerSettingsOf(const MethodSettings& m) {
  PathTracerSettings s = m.section<PathTracerSettings>();
  s.samplesPerPixel = m.samplesPerPixel;
  s.seed = m.seed;
  s.checkpointDir = m.cacheDir;
  s.processes = m.processes;
  s.irradiance = m.irradiancePictures;
  return s;
}

class PathTracerMethod final : public RadiosityMethod {
 public:
  std::string name() const override { return "pathtrace"; }
  std::string settingsGroup() const override { return kGroup; }
  MethodCapabilities capabilities() const override {
    MethodCapabilities c;
    c.surfaceSolution = false;
    c.processes = true;
    return c;
  }
  std::vector<SettingDeclaration> settingDeclarations() const override {
    return {sectionField("max_depth", kGroup, &PathTracerSettings::maxDepth,
                         "Path tracer bounce limit (Russian roulette ends paths long before)",
                         {1, 100000})};
  }
  int defaultSamplesPerPixel() const override { return PathTracerSettings{}.samplesPerPixel; }

  RenderedPicture renderPicture(const Scene& scene, const RayCaster& caster, const Camera& camera,
                                const MethodSettings& settings,
                                const ProgressCallback& progress) const override {
    PathTracedImage result =
        renderPathTraced(scene, caster, camera, pathTracerSettingsOf(settings), progress);
    RenderedPicture picture;
    picture.image = std::move(result.image);
    picture.rays = result.stats.rays;
    picture.warnings = std::move(result.stats.warnings);
    if (result.stats.resumedTiles > 0)
      picture.resumed = fmt::format("went on from a checkpoint: {} tiles were done before",
                                    result.stats.resumedTiles);
    return picture;
  }

  EstimatedObjects estimateObjects(const Scene& scene, const RayCaster& caster, int pointsPerObject,
                                   const MethodSettings& settings,
                                   const ProgressCallback& progress) const override {
    PathTracerStats stats;
    EstimatedObjects estimated;
    estimated.objects = estimateObjectRadiometry(scene, caster, pointsPerObject,
                                                 pathTracerSettingsOf(settings), &stats, progress);
    estimated.rays = stats.rays;
    return estimated;
  }

  EstimatedSensors estimateSensors(const Scene& scene, const RayCaster& caster,
                                   std::span<const SensorPoint> points,
                                   const SensorSettings& sensors, const MethodSettings& settings,
                                   const ProgressCallback& progress) const override {
    PathTracerStats stats;
    EstimatedSensors estimated;
    estimated.irradiance = estimateSensorIrradiance(
        scene, caster, points, sensors, pathTracerSettingsOf(settings), &stats, progress);
    estimated.rays = stats.rays;
    return estimated;
  }
};

}  // namespace

std::unique_ptr<RadiosityMethod> makePathTracerMethod() {
  return std::make_unique<PathTracerMethod>();
}

}  // namespace rad
