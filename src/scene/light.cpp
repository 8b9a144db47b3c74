#include <radiosity/scene.h>

#include <cmath>
#include <glm/gtc/constants.hpp>

namespace rad {

const char* lightTypeName(LightType type) {
  switch (type) {
    case LightType::Point:
      return "point";
    case LightType::Spot:
      return "spot";
    case LightType::Ies:
      return "ies";
    case LightType::Object:
      return "object";
    case LightType::Directional:
      return "directional";
    case LightType::Sky:
      break;
  }
  return "sky";
}

namespace {

// An orthonormal frame around the light's axis for the IES table: +z against the aim (IES
// photometry looks down -z), x and y completing a right-handed frame.
void luminaireFrame(const Vec3& aim, Vec3& x, Vec3& y, Vec3& z) {
  z = -glm::normalize(aim);
  const Vec3 helper = std::abs(z.y) < 0.99f ? Vec3(0.0f, 1.0f, 0.0f) : Vec3(1.0f, 0.0f, 0.0f);
  x = glm::normalize(glm::cross(helper, z));
  y = glm::cross(z, x);
}

// Fraction of the axial intensity at angle acos(cosTheta) off the axis: 1 inside the inner
// cone, 0 outside the outer one, a smoothstep between (as most real-time engines do).
float spotFalloff(float cosTheta, float innerAngleDeg, float outerAngleDeg) {
  const float cosOuter = std::cos(glm::radians(outerAngleDeg));
  const float cosInner = std::cos(glm::radians(innerAngleDeg));
  if (cosTheta <= cosOuter) return 0.0f;
  if (cosTheta >= cosInner) return 1.0f;
  const float t = (cosTheta - cosOuter) / (cosInner - cosOuter);
  return t * t * (3.0f - 2.0f * t);
}

}  // namespace

Color Light::intensityToward(const Vec3& toward) const {
  switch (type) {
    case LightType::Point:
    case LightType::Directional:  // its irradiance, along its direction only
      return intensity;
    case LightType::Spot:
      return intensity * spotFalloff(glm::dot(toward, direction), innerAngleDeg, outerAngleDeg);
    case LightType::Ies: {
      if (!ies) return Color(0.0f);
      Vec3 x, y, z;
      luminaireFrame(direction, x, y, z);
      const double cd =
          ies->candelaToward(glm::dot(toward, x), glm::dot(toward, y), glm::dot(toward, z));
      return intensity * float(cd);
    }
    case LightType::Object: {
      Color sum(0.0f);
      for (int k = 0; k < 6; ++k) sum += lobes[size_t(k)] * axisLobe(toward, k);
      return intensity * sum;  // intensity: a dimmer on it (1 as made)
    }
    case LightType::Sky:
      return intensity * sky.relativeRadiance(-toward);
  }
  return Color(0.0f);
}

Color Light::power() const {
  switch (type) {
    case LightType::Point:
      return intensity * (4.0f * glm::pi<float>());
    case LightType::Spot: {
      // Integral of the profile over the sphere: 2 pi * integral over cos(theta) of the falloff,
      // evaluated by the midpoint rule in cos(theta) (the smoothstep has no simple antiderivative
      // in theta; 256 steps are accurate to far below 1e-4).
      const double cosOuter = std::cos(glm::radians(double(outerAngleDeg)));
      const int steps = 256;
      double integral = 0.0;
      for (int i = 0; i < steps; ++i) {
        const double c = cosOuter + (1.0 - cosOuter) * (i + 0.5) / steps;
        integral += spotFalloff(float(c), innerAngleDeg, outerAngleDeg);
      }
      integral *= (1.0 - cosOuter) / steps;
      return intensity * float(2.0 * glm::pi<double>() * integral);
    }
    case LightType::Ies:
      // Lumens are candela x steradians, so the flux integral scales the same way as intensity.
      return ies ? intensity * float(ies->totalFlux()) : Color(0.0f);
    case LightType::Object: {
      // Each lobe max(0, d . e) integrates to pi over the sphere.
      Color sum(0.0f);
      for (const Color& lobe : lobes) sum += lobe;
      return intensity * sum * glm::pi<float>();
    }
    case LightType::Directional:
    case LightType::Sky:
      break;
  }
  return Color(0.0f);
}

}  // namespace rad
