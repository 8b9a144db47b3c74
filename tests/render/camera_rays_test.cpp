// PinholeCamera: the geometry of primary rays for rad::Camera (vertical fov, row 0 at the top).
#include "render/camera_rays.h"

#include <gtest/gtest.h>
#include <radiosity/error.h>

#include <cmath>

namespace rad {
namespace {

Camera lookDownZ(int width, int height, float fovDeg) {
  Camera c;
  c.eye = Vec3(1, 2, 3);
  c.target = Vec3(1, 2, 0);
  c.up = Vec3(0, 1, 0);
  c.fovDeg = fovDeg;
  c.width = width;
  c.height = height;
  return c;
}

TEST(PinholeCamera, CentreAndEdgesFollowTheFieldOfView) {
  const PinholeCamera cam(lookDownZ(9, 5, 60.0f));
  const Ray centre = cam.ray(4, 2, {0.5f, 0.5f});
  EXPECT_NEAR(glm::length(centre.origin - Vec3(1, 2, 3)), 0.0f, 1e-6f);
  EXPECT_NEAR(centre.direction.z, -1.0f, 1e-6f);
  // Top edge of the image (row 0, offset 0) is fov/2 = 30 degrees above the axis.
  const Ray top = cam.ray(4, 0, {0.5f, 0.0f});
  EXPECT_NEAR(std::atan2(top.direction.y, -top.direction.z), glm::radians(30.0f), 1e-5f);
  // Right edge: the horizontal half-width is the vertical one times the aspect 9/5.
  const Ray right = cam.ray(8, 2, {1.0f, 0.5f});
  EXPECT_NEAR(right.direction.x / -right.direction.z, std::tan(glm::radians(30.0f)) * 9.0f / 5.0f,
              1e-5f);
  EXPECT_GT(right.direction.x, 0.0f);  // x grows to the right for a camera looking down -z
  EXPECT_NEAR(glm::length(right.direction), 1.0f, 1e-6f);
}

TEST(PinholeCamera, RejectsBadCameras) {
  EXPECT_THROW(PinholeCamera(lookDownZ(0, 5, 60.0f)), InputError);
  EXPECT_THROW(PinholeCamera(lookDownZ(5, 5, 180.0f)), InputError);
  EXPECT_THROW(PinholeCamera(lookDownZ(5, 5, 0.0f)), InputError);
  Camera same = lookDownZ(5, 5, 60.0f);
  same.target = same.eye;
  EXPECT_THROW(PinholeCamera{same}, InputError);
  Camera parallel = lookDownZ(5, 5, 60.0f);
  parallel.up = Vec3(0, 0, 1);
  EXPECT_THROW(PinholeCamera{parallel}, InputError);
}

}  // namespace
}  // namespace rad
