// Cameras in OpenCV conventions: our projection equals cv::projectPoints (distortion included),
// look_at gives the documented image orientation, and cameras.yml round-trips.
#include <gtest/gtest.h>

#include <filesystem>

#include <opencv2/calib3d.hpp>

#include "core/error.hpp"
#include "vision/camera.hpp"

using namespace finverse::vision;

TEST(Camera, ProjectionMatchesOpenCV) {
  const auto rig = default_rig({"side", "back", "ventral"}, 0.01, 512, 512);
  ASSERT_EQ(rig.size(), 3u);
  std::vector<cv::Point3d> pts;
  for (double x : {0.0, 0.004, 0.01})
    for (double y : {-0.005, 0.0, 0.004})
      for (double z : {-0.0075, 0.0, 0.0075}) pts.emplace_back(x, y, z);
  for (const auto& cam : rig) {
    std::vector<cv::Point2d> ref;
    cv::projectPoints(pts, cam.rvec, cam.tvec, cv::Mat(cam.K), cv::Mat(cam.dist), ref);
    for (std::size_t i = 0; i < pts.size(); ++i) {
      double depth = 0;
      const auto p = cam.project(cv::Vec3d(pts[i].x, pts[i].y, pts[i].z), &depth);
      EXPECT_NEAR(p.x, ref[i].x, 1e-9) << cam.name;
      EXPECT_NEAR(p.y, ref[i].y, 1e-9) << cam.name;
      EXPECT_GT(depth, 0);
      // The fin stays inside the image.
      EXPECT_GT(p.x, 0);
      EXPECT_LT(p.x, cam.width - 1);
      EXPECT_GT(p.y, 0);
      EXPECT_LT(p.y, cam.height - 1);
    }
  }
}

TEST(Camera, LookAtOrientation) {
  // Side view: downstream (+x) to the right, dorsal (+z) up in the image (y down).
  const auto cam = look_at("side", 100, 100, 500, {0, -1, 0}, {0, 0, 0}, {0, 0, 1});
  const auto o = cam.project({0, 0, 0}), px = cam.project({0.01, 0, 0}), pz = cam.project({0, 0, 0.01});
  EXPECT_NEAR(o.x, 49.5, 1e-12);
  EXPECT_GT(px.x, o.x);
  EXPECT_LT(pz.y, o.y);
  const auto c = cam.center();
  EXPECT_NEAR(c[1], -1, 1e-12);
  EXPECT_THROW(look_at("bad", 10, 10, 5, {0, 0, -1}, {0, 0, 0}, {0, 0, 1}), finverse::Error);
}

TEST(Camera, YamlRoundTrip) {
  const auto dir = std::filesystem::temp_directory_path() / ("vision_cam_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto rig = default_rig({"back", "ventral"}, 0.01, 640, 480);
  write_cameras(dir / "cameras.yml", rig);
  const auto back = read_cameras(dir / "cameras.yml");
  ASSERT_EQ(back.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(back[i].name, rig[i].name);
    EXPECT_EQ(back[i].width, 640);
    EXPECT_EQ(back[i].height, 480);
    for (int k = 0; k < 9; ++k) EXPECT_DOUBLE_EQ(back[i].K(k / 3, k % 3), rig[i].K(k / 3, k % 3));
    for (int k = 0; k < 5; ++k) EXPECT_DOUBLE_EQ(back[i].dist[k], rig[i].dist[k]);
    for (int k = 0; k < 3; ++k) {
      EXPECT_DOUBLE_EQ(back[i].rvec[k], rig[i].rvec[k]);
      EXPECT_DOUBLE_EQ(back[i].tvec[k], rig[i].tvec[k]);
    }
  }
  EXPECT_THROW(read_cameras(dir / "missing.yml"), finverse::Error);
  EXPECT_THROW(default_rig({"top"}, 0.01, 64, 64), finverse::Error);
  std::filesystem::remove_all(dir);
}
