// Ray root and tip keypoints in the skeleton fit (vision/keypoint_residual.hpp) and the
// DeepLabCut / Anipose files they come in (vision/keypoint_files.hpp): a synthetic record whose
// keypoints alone (no silhouettes) give back the known pose, and the files written and read back.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "mesh/fin_template.hpp"
#include "vision/camera.hpp"
#include "vision/keypoint_files.hpp"
#include "vision/skeleton_fit.hpp"
#include "vision/tracker.hpp"

using namespace finverse;
using namespace finverse::vision;

namespace {

mesh::FinTemplate small_fin() {
  mesh::CaudalFinParams p;
  p.rays = 5;
  p.points_per_ray = 9;
  return mesh::make_caudal_fin(p);
}

// Root moved and turned, every ray flapped about its root (about z) by an amount that grows
// across the span, no twist (the one rotation a ray's two ends cannot show). A common flap of the
// rays and the root's turn about z move the fin alike (the roots lie on that axis): only their sum
// per ray is compared.
Pose known_pose(const Skeleton& s) {
  Pose p = Pose::rest(s);
  p.p[0] = 0.05, p.p[1] = 0.1, p.p[2] = -0.03;
  p.p[3] = 0.02, p.p[4] = -0.03, p.p[5] = 0.25;
  for (std::size_t r = 0; r < s.rays; ++r)
    p.p[3 + 3 * s.joint(r, 0) + 2] = 0.01 * (static_cast<double>(r) - 0.5 * static_cast<double>(s.rays - 1));
  return p;
}

}  // namespace

TEST(KeypointFit, KeypointsAloneRecoverKnownJointAngles) {
  const auto fin = small_fin();
  const auto model = make_tracking_model(fin, 2, 1);
  const auto& s = model.skeleton;
  const Pose truth = known_pose(s);
  const auto X = skin(model.binding, forward_kinematics(s, truth));
  const auto ends = model.ray_ends();
  std::vector<ViewData> views;
  for (const auto& c : default_rig({"side", "back", "ventral"}, fin.chord, 512, 512)) {
    ViewData v;  // no frame: no silhouette, the keypoints alone
    v.camera = c;
    views.push_back(v);
  }
  for (const bool three_d : {false, true}) {
    FrameKeypoints k;
    for (std::size_t r = 0; r < s.rays; ++r)
      for (RayEnd e : {RayEnd::root, RayEnd::tip}) {
        const auto v = static_cast<std::size_t>(ends.vertex(r, e));
        const cv::Vec3d x(X(v, 0), X(v, 1), X(v, 2));
        if (three_d) k.world.push_back({r, e, x});
        else
          for (std::size_t w = 0; w < 2; ++w) k.image.push_back({r, e, w, views[w].camera.project(x)});
      }
    // Keypoints weighted far above the priors (which pull neighbouring rays together), so the
    // pose is the keypoints' alone.
    FitOptions fo;
    fo.keypoints.weight = 100;
    SkeletonFitter fitter(s, model.binding, model.surface.triangles, {}, fo);
    fitter.set_ray_ends(ends);
    const auto fit = fitter.fit(views, Pose::rest(s), nullptr, 60, &k);
    for (std::size_t i = 0; i < 5; ++i) EXPECT_NEAR(fit.pose.p[i], truth.p[i], 1e-3) << (three_d ? "3-D" : "2-D") << " root parameter " << i;
    for (std::size_t r = 0; r < s.rays; ++r)
      for (int c = 0; c < 3; ++c) {
        const std::size_t i = 3 + 3 * s.joint(r, 0) + static_cast<std::size_t>(c);
        const double root_turn = c == 2 ? 1.0 : 0.0;
        EXPECT_NEAR(fit.pose.p[i] + root_turn * fit.pose.p[5], truth.p[i] + root_turn * truth.p[5], 1e-3) << (three_d ? "3-D" : "2-D") << " ray " << r + 1 << " rotation " << c;
      }
    if (!three_d) {
      EXPECT_LT(fit.keypoint_rms_px, 0.05);
    }
  }
}

TEST(KeypointFiles, DeepLabCutAndAniposeLayoutsReadBack) {
  const auto fin = small_fin();
  const auto model = make_tracking_model(fin, 2, 1);
  const auto& s = model.skeleton;
  NdArray<double> points({2, model.binding.size(), 3});
  const auto X = skin(model.binding, forward_kinematics(s, known_pose(s)));
  for (std::size_t f = 0; f < 2; ++f) std::copy(X.data.begin(), X.data.end(), points.data.begin() + f * X.size());
  const auto cams = default_rig({"side"}, fin.chord, 512, 512);
  const auto dir = std::filesystem::temp_directory_path();
  write_deeplabcut_csv(dir / "finverse_kp_side.csv", fitted_ray_ends({4, 7}, points, model.ray_ends(), &cams[0], 1.0));
  write_anipose_csv(dir / "finverse_kp_3d.csv", fitted_ray_ends({4, 7}, points, model.ray_ends(), nullptr, 1e-3));
  const auto dlc = read_deeplabcut_csv(dir / "finverse_kp_side.csv");
  const auto ani = read_anipose_csv(dir / "finverse_kp_3d.csv");
  ASSERT_EQ(dlc.bodyparts.size(), 2 * s.rays);
  EXPECT_EQ(dlc.bodyparts[3], "ray2_tip");
  EXPECT_EQ(dlc.frames, (std::vector<long>{4, 7}));
  EXPECT_EQ(ani.frames, (std::vector<long>{4, 7}));
  const auto rec = keypoint_record({{0, &dlc}}, &ani, 1e-3, 0.5, s.rays);
  ASSERT_EQ(rec.size(), 2u);
  const auto& k = rec.at(7);
  ASSERT_EQ(k.image.size(), 2 * s.rays);
  ASSERT_EQ(k.world.size(), 2 * s.rays);
  const auto v = static_cast<std::size_t>(model.ray_ends().vertex(1, RayEnd::tip));
  const cv::Vec3d x(X(v, 0), X(v, 1), X(v, 2));
  EXPECT_LT(cv::norm(k.image[3].uv - cams[0].project(x)), 1e-6);
  EXPECT_LT(cv::norm(k.world[3].X - x), 1e-9);
  EXPECT_EQ(k.world[3].ray, 1u);
  EXPECT_EQ(k.world[3].end, RayEnd::tip);

  // DeepLabCut's own layout: a multi-animal header row, an image name as the frame, a low
  // likelihood left out, another bodypart ignored; a ray the template lacks is an error.
  std::ofstream(dir / "finverse_kp_dlc.csv") << "scorer,DLC_r50,DLC_r50,DLC_r50,DLC_r50,DLC_r50,DLC_r50\n"
                                                "individuals,fish,fish,fish,fish,fish,fish\n"
                                                "bodyparts,ray1_root,ray1_root,ray1_root,eye,eye,eye\n"
                                                "coords,x,y,likelihood,x,y,likelihood\n"
                                                "labeled-data/clip/img012.png,10.5,20.25,0.99,1,2,0.9\n"
                                                "labeled-data/clip/img013.png,11,21,0.1,1,2,0.9\n";
  const auto own = read_deeplabcut_csv(dir / "finverse_kp_dlc.csv");
  EXPECT_EQ(own.frames, (std::vector<long>{12, 13}));
  const auto own_rec = keypoint_record({{0, &own}}, nullptr, 1e-3, 0.6, s.rays);
  ASSERT_EQ(own_rec.size(), 1u);
  EXPECT_EQ(own_rec.at(12).image.at(0).uv, cv::Point2d(10.5, 20.25));
  EXPECT_THROW(keypoint_record({{0, &own}}, nullptr, 1e-3, 0.6, 0), Error);
  std::ofstream(dir / "finverse_kp_bad.csv") << "frame,x,y\n0,1,2\n";
  EXPECT_THROW(read_deeplabcut_csv(dir / "finverse_kp_bad.csv"), Error);
  for (const char* f : {"finverse_kp_side.csv", "finverse_kp_3d.csv", "finverse_kp_dlc.csv", "finverse_kp_bad.csv"})
    std::filesystem::remove(dir / f);
}
