#pragma once
// Primary rays of a pinhole camera (rad::Camera: vertical field of view, image row 0 at the top).

#include <radiosity/ray_caster.h>
#include <radiosity/scene.h>

namespace rad {

class PinholeCamera {
 public:
  /// Throws InputError("camera", ...) for a non-positive size, a field of view outside
  /// (0, 180) degrees, eye == target or an up vector parallel to the view direction.
  explicit PinholeCamera(const Camera& camera);

  /// The ray through pixel (x, y) at `offset` in [0,1)^2 inside it (0.5, 0.5 is the centre);
  /// unit direction, origin at the eye.
  Ray ray(int x, int y, Vec2 offset) const;

  int width() const { return width_; }
  int height() const { return height_; }

 private:
  Vec3 eye_, forward_, right_, up_;  // right_ and up_ are scaled to the image plane at distance 1
  int width_, height_;
};

}  // namespace rad
