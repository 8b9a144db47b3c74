// The patch method's solution file: its patches by node address (the base mesh refined to them
// gives the same quadtree, patch order and vertex values, so a loaded solution renders bit for
// bit as the saved one did), and per patch the irradiance and its indirect part (per light group
// when they were solved apart), the lights' direct light and the radiosity.
#include <radiosity/error.h>
#include <radiosity/patch_radiosity.h>

#include <glm/gtc/constants.hpp>

#include "patch/patch_model_state.h"
#include "patch/patch_radiosity_impl.h"
#include "scene/solution_file.h"

namespace rad {

void PatchRadiosity::save(const std::string& path, const SolverSettings& settings) const {
  const Impl& m = *impl_;
  std::string out = solutionFileStart("patch", *m.scene, m.lights, settings);
  const size_t n = m.mesh->size();
  put(out, uint64_t(n));
  for (const Patch& p : m.mesh->patches()) put(out, m.mesh->nodeAddress(p.node));
  const bool apart = m.mix.apart();
  put(out, uint8_t(apart));
  if (apart) {
    put(out, uint64_t(m.groupIrradiance.size()));
    for (size_t g = 0; g < m.groupIrradiance.size(); ++g) {
      putArray<Color>(out, m.groupIrradiance[g]);
      putArray<Color>(out, m.groupIndirect[g]);
    }
    putArray<Color>(out, m.mix.scales());
  } else {
    put(out, uint64_t(1));
    putArray<Color>(out, m.solution.irradiance);
    putArray<Color>(out, m.indirect);
    putArray<Color>(out, m.solution.radiosity);
  }
  put(out, uint64_t(m.lightDirect.size()));
  putArray<Color>(out, m.lightDirect);
  writeSolutionFile(path, out);
}

// The payload into this solution, whose mesh is the model's base mesh.
void PatchRadiosity::Impl::readSolution(const SolutionFile& file, ByteReader in) {
  Impl& m = *this;
  const uint64_t n = in.get<uint64_t>();
  const std::vector<uint64_t> leaves = in.array<uint64_t>(n);
  if (!m.mesh->refineToLeaves(leaves))
    file.refuse("its patches are not a refinement of this scene's base mesh");
  for (uint32_t p = 0; p < n; ++p)
    if (m.mesh->nodeAddress(m.mesh->patches()[p].node) != leaves[p])
      file.refuse("its patches are in another order");
  const bool apart = in.get<uint8_t>() != 0;
  m.mix = LightGroupMix(*m.scene, m.lights, apart);
  const uint64_t groups = in.get<uint64_t>();
  if (groups != (apart ? m.mix.groups().size() : 1))
    file.refuse("it has another number of light groups");
  for (uint64_t g = 0; g < groups; ++g) {
    m.groupIrradiance.push_back(file.radiometry(in, n, "irradiance"));
    m.groupIndirect.push_back(file.radiometry(in, n, "indirect irradiance"));
  }
  if (apart) {
    m.mix.setScales(in.array<Color>(groups));
    m.combineGroups();
  } else {
    m.solution.irradiance = std::move(m.groupIrradiance[0]);
    m.indirect = std::move(m.groupIndirect[0]);
    m.groupIrradiance.clear();
    m.groupIndirect.clear();
    m.solution.radiosity = file.radiometry(in, n, "radiosity");
    for (const Patch& p : m.mesh->patches())
      m.solution.emitted.push_back(glm::pi<float>() * m.scene->materials[p.material].emission *
                                   p.emissionTint);
  }
  const uint64_t direct = in.get<uint64_t>();
  if (direct != 0 && direct != n) file.refuse("its direct light is not one value per patch");
  m.lightDirect = file.radiometry(in, direct, "direct light");
  if (!in.atEnd()) file.refuse("trailing bytes after its arrays");
}

PatchRadiosity PatchModel::load(const std::string& path, std::span<const Light> lights) const {
  const SolutionFile file(path);
  file.checkFor("patch", *state_->scene, lights);
  auto impl = std::make_unique<PatchRadiosity::Impl>(state_, lights);
  file.readPayload([&](ByteReader in) { impl->readSolution(file, in); });
  impl->shadeVertices();
  impl->recordMesh();
  impl->stats.solver = "loaded from " + path;
  return PatchRadiosity(std::move(impl));
}

}  // namespace rad
