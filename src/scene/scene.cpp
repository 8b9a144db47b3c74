#include <radiosity/scene.h>

#include <cmath>
#include <glm/gtc/constants.hpp>

namespace rad {

Vec3 Scene::triangleNormal(uint32_t t) const {
  const UVec3& tri = triangles[t];
  const Vec3d a = positions[tri.x], b = positions[tri.y], c = positions[tri.z];
  return Vec3(glm::normalize(glm::cross(b - a, c - a)));
}

float Scene::triangleArea(uint32_t t) const {
  const UVec3& tri = triangles[t];
  const Vec3d a = positions[tri.x], b = positions[tri.y], c = positions[tri.z];
  return float(0.5 * glm::length(glm::cross(b - a, c - a)));
}

Bounds Scene::bounds() const {
  Bounds b;
  for (const UVec3& t : triangles)
    for (int k = 0; k < 3; ++k) b.extend(positions[t[k]]);
  for (const Light& light : lights) b.extend(light.position);
  return b;
}

Color Scene::emittedPower() const {
  Vec3d power(0.0);
  for (uint32_t t = 0; t < triangles.size(); ++t) {
    const Material& m = materialOf(t);
    if (!m.emits()) continue;
    const double sides = m.twoSided ? 2.0 : 1.0;
    power += Vec3d(m.emission) * (glm::pi<double>() * sides * triangleArea(t));
  }
  for (const Light& light : lights) power += Vec3d(light.power());
  return Color(power);
}

bool Scene::hasEmitters() const {
  for (uint32_t t = 0; t < triangles.size(); ++t)
    if (materialOf(t).emits()) return true;
  for (const Light& light : lights)
    if (maxComponent(light.power()) > 0.0f) return true;
  return false;
}

std::string cameraProblem(const Camera& camera) {
  const Vec3 view = camera.target - camera.eye;
  if (!(glm::length(view) > 0.0f)) return "target: eye and target coincide";
  if (!(glm::length(glm::cross(glm::normalize(view), camera.up)) > 1e-6f * glm::length(camera.up)))
    return "up: up is zero or parallel to the viewing direction";
  return "";
}

Camera Scene::cameraOrDefault() const {
  if (camera) return *camera;
  Camera c;
  const Bounds b = bounds();
  if (b.empty()) return c;
  // Look along -z at the centre, far enough that the bounding sphere fits the field of view.
  const float radius = 0.5f * b.diagonal();
  const float distance = radius / std::sin(glm::radians(0.5f * c.fovDeg));
  c.target = b.center();
  c.eye = b.center() + Vec3(0.0f, 0.0f, b.extent().z * 0.5f + distance);
  return c;
}

}  // namespace rad
