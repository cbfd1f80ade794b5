// Test fixture shared by the silhouette-coverage and coverage-residual tests: a 64 x 64 pinhole
// camera on the -y axis looking at the origin, so that a point (x, 0, z) of the plane y = 0 maps to
// pixel u = cx + f x / d, v = cy - f z / d, and world lengths convert to pixels by f / d.
#pragma once

#include <numbers>

#include <opencv2/core.hpp>

#include "vision/camera.hpp"

namespace finverse::vision::test {

constexpr double kF = 500, kD = 0.1;  // focal length (px), distance to the plane y = 0 (m)

inline Camera front_camera() {
  Camera c;
  c.name = "front";
  c.width = c.height = 64;
  c.K = cv::Matx33d(kF, 0, 31.5, 0, kF, 31.5, 0, 0, 1);
  c.rvec = cv::Vec3d(std::numbers::pi / 2, 0, 0);  // camera z = world +y, camera y = world -z
  c.tvec = cv::Vec3d(0, 0, kD);
  return c;
}

}  // namespace finverse::vision::test
