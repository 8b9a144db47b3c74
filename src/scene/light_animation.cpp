// Lights over time: keyframed paths and spins, evaluated at a time (Light::at), so that every
// method and command sees an animated scene as the plain scene of that instant.
#include <radiosity/scene.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>

namespace rad {

namespace {

// v turned by `radians` about the unit `axis` (Rodrigues' formula).
Vec3 rotate(const Vec3& v, const Vec3& axis, float radians) {
  const float c = std::cos(radians), s = std::sin(radians);
  return v * c + glm::cross(axis, v) * s + axis * (glm::dot(axis, v) * (1.0f - c));
}

// The unit vector a fraction s of the way from unit a to unit b along the great circle.
Vec3 slerp(const Vec3& a, const Vec3& b, float s) {
  const float angle = std::acos(std::clamp(glm::dot(a, b), -1.0f, 1.0f));
  if (angle < 1e-6f) return b;
  Vec3 axis = glm::cross(a, b);
  if (glm::length(axis) < 1e-6f) {  // opposite: any perpendicular axis turns one into the other
    axis = glm::cross(a, std::abs(a.x) < 0.9f ? Vec3(1, 0, 0) : Vec3(0, 1, 0));
  }
  return glm::normalize(rotate(a, glm::normalize(axis), s * angle));
}

// A field's value at `t` from the keyframes that set it (`field` picks it), or nullopt if none
// does: held before the first and after the last, interpolated by `mix` between.
template <class T, class Field, class Mix>
std::optional<T> track(const std::vector<LightKeyframe>& path, double t, Field field, Mix mix) {
  const LightKeyframe* before = nullptr;
  for (const LightKeyframe& k : path) {
    const std::optional<T>& value = k.*field;
    if (!value) continue;
    if (k.t >= t) {
      if (!before || k.t <= before->t) return value;
      const float s = float((t - before->t) / (k.t - before->t));
      return mix(*(before->*field), *value, s);
    }
    before = &k;
  }
  return before ? before->*field : std::nullopt;
}

}  // namespace

Light Light::at(double seconds) const {
  Light out = *this;
  auto lerp = [](const auto& a, const auto& b, float s) { return a + (b - a) * s; };
  if (auto p = track<Vec3>(path, seconds, &LightKeyframe::position, lerp)) out.position = *p;
  if (auto d = track<Vec3>(path, seconds, &LightKeyframe::direction, slerp)) out.direction = *d;
  if (auto i = track<Color>(path, seconds, &LightKeyframe::intensity, lerp)) out.intensity = *i;
  const float rate = glm::length(spinDegPerS);
  if (rate > 0.0f)
    out.direction = glm::normalize(
        rotate(out.direction, spinDegPerS / rate, glm::radians(rate) * float(seconds)));
  return out;
}

std::vector<Light> Scene::lightsAt(double seconds) const {
  std::vector<Light> out;
  for (const Light& light : lights) out.push_back(light.at(seconds));
  return out;
}

}  // namespace rad
