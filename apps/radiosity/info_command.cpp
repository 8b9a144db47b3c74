// `radiosity info SCENE`: what a scene holds, and what is wrong with it.
#include <fmt/format.h>
#include <radiosity/scene_loader.h>
#include <radiosity/solver_settings.h>

#include <CLI/CLI.hpp>
#include <memory>
#include <ostream>

#include "command_support.h"
#include "commands.h"

namespace rad::cli {

namespace {

// The scene's length unit, and its area and emitted power in it: pi Ke A is watts, Ke being
// radiance per square scene unit (a scene in mm with Ke of a few tens emits hundreds of kW).
void printUnitAndPower(const Scene& scene, std::ostream& out) {
  const LengthUnit& unit = scene.unit;
  out << (unit.known() ? fmt::format("unit       {} ({:g} m)\n", unit.name, unit.metres)
                       : "unit       unknown (lengths in scene units; a scene file's \"unit\" "
                         "names it)\n");
  const Color power = scene.emittedPower();
  out << fmt::format("emitted    ({:.6g}, {:.6g}, {:.6g}) W (Ke taken per {}^2)\n", power.r,
                     power.g, power.b, unit.symbol());
  double area = 0.0;
  for (const Face& f : scene.faces) area += f.area;
  out << fmt::format("area       {:.6g} {}^2", area, unit.symbol());
  if (unit.known() && unit.name != "m")
    out << fmt::format(" ({:.6g} m^2)", area * unit.metres * unit.metres);
  out << "\n";
}

int runInfo(const std::string& sceneName, Console& console) {
  const Scene scene = loadScene(sceneName);
  // Its "solver" values judged against the methods' settings table, as a run would judge them.
  resolveMethodSettings(scene.solver, {}, scene.name);
  std::ostream& out = console.out();
  size_t emissive = 0, textured = 0;
  for (const Material& m : scene.materials) {
    emissive += m.emits() ? 1 : 0;
    textured += m.rhoTexture || m.emissionTexture ? 1 : 0;
  }
  out << fmt::format("scene      {}\n", scene.name);
  out << fmt::format("objects    {}\n", scene.objects.size());
  out << fmt::format("triangles  {}\n", scene.triangles.size());
  out << fmt::format("faces      {}\n", scene.faces.size());
  out << fmt::format("materials  {} ({} emissive, {} textured)\n", scene.materials.size(), emissive,
                     textured);
  for (const Material& m : scene.materials)
    for (const TextureMap* map : {&m.rhoTexture, &m.emissionTexture})
      if (*map)
        out << fmt::format("  {} {}: {} ({} x {} texels)\n", m.name,
                           map == &m.rhoTexture ? "colour" : "emission", map->texture->name(),
                           map->texture->width(), map->texture->height());
  out << fmt::format("lights     {}\n", scene.lights.size());
  for (const Light& light : scene.lights) {
    const Color& i = light.intensity;
    if (light.positional())
      out << fmt::format("  {:<5} at ({:g}, {:g}, {:g}), intensity ({:g}, {:g}, {:g}) W/sr\n",
                         lightTypeName(light.type), light.position.x, light.position.y,
                         light.position.z, i.r, i.g, i.b);
    else if (light.type == LightType::Sky)
      out << fmt::format("  sky {}, radiance ({:g}, {:g}, {:g}) W/(sr {}^2){}\n",
                         skyModelName(light.sky.model), i.r, i.g, i.b, scene.unit.symbol(),
                         light.sky.model == SkyModel::Uniform ? "" : " at the zenith");
    else  // the sun: a way, and the irradiance on a plane facing it
      out << fmt::format(
          "  {} along ({:.4g}, {:.4g}, {:.4g}), irradiance ({:g}, {:g}, {:g}) W/{}^2\n",
          lightTypeName(light.type), light.direction.x, light.direction.y, light.direction.z, i.r,
          i.g, i.b, scene.unit.symbol());
  }
  out << fmt::format("dynamic    {}\n", scene.dynamicObjects.size());
  for (const DynamicObject& object : scene.dynamicObjects)
    out << fmt::format("  {} ({} triangles, {} keyframes)\n", object.name,
                       object.mesh->triangles.size(), object.path.size());
  const Bounds b = scene.bounds();
  if (!b.empty())
    out << fmt::format("bounds     ({:g}, {:g}, {:g}) - ({:g}, {:g}, {:g})\n", b.min.x, b.min.y,
                       b.min.z, b.max.x, b.max.y, b.max.z);
  printUnitAndPower(scene, out);
  std::vector<std::string> warnings = scene.warnings;
  if (!scene.hasEmitters())
    warnings.push_back("no emitting surface and no light: renders will be black");
  out << fmt::format("warnings   {}\n", warnings.size());
  for (const std::string& w : warnings) out << "  " << w << "\n";
  return 0;
}

}  // namespace

void addInfoCommand(CLI::App& app, Console& console, CommandAction& action) {
  auto scene = std::make_shared<std::string>();
  CLI::App* sub =
      app.add_subcommand("info", "Print what a scene holds: counts, bounds, power, warnings");
  addSceneArgument(*sub, *scene);
  sub->callback([scene, &console, &action] {
    action = [scene, &console] { return runInfo(*scene, console); };
  });
}

}  // namespace rad::cli
