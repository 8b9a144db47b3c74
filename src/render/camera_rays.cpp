#include "render/camera_rays.h"

#include <fmt/format.h>
#include <radiosity/error.h>

#include <cmath>

namespace rad {

PinholeCamera::PinholeCamera(const Camera& c) : width_(c.width), height_(c.height) {
  if (c.width <= 0 || c.height <= 0)
    throw InputError("camera", fmt::format("image size {}x{} must be positive", c.width, c.height));
  if (!(c.fovDeg > 0.0f && c.fovDeg < 180.0f))
    throw InputError("camera", fmt::format("fov_deg {} out of range (0, 180)", c.fovDeg));
  const Vec3 view = c.target - c.eye;
  if (!(glm::length(view) > 0.0f)) throw InputError("camera", "eye and target coincide");
  forward_ = glm::normalize(view);
  const Vec3 side = glm::cross(forward_, c.up);
  if (!(glm::length(side) > 1e-6f * glm::length(c.up)))
    throw InputError("camera", "up vector is zero or parallel to the view direction");
  const float halfHeight = std::tan(glm::radians(0.5f * c.fovDeg));
  const float aspect = float(c.width) / float(c.height);
  right_ = glm::normalize(side) * (halfHeight * aspect);
  up_ = glm::normalize(glm::cross(right_, forward_)) * halfHeight;
  eye_ = c.eye;
}

Ray PinholeCamera::ray(int x, int y, Vec2 offset) const {
  const float sx = 2.0f * (float(x) + offset.x) / float(width_) - 1.0f;
  const float sy = 1.0f - 2.0f * (float(y) + offset.y) / float(height_);
  Ray r;
  r.origin = eye_;
  r.direction = glm::normalize(forward_ + sx * right_ + sy * up_);
  return r;
}

}  // namespace rad
