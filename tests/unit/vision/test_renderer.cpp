// The renderer: deterministic for a given noise key, different for another key, the fin lands
// where the camera projects it, rays are darker than membrane, motion blur smears, and fin-synth
// writes identical files on identical runs.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "vision/kinematic_model.hpp"
#include "vision/renderer.hpp"

using namespace finverse;
using namespace finverse::vision;
namespace fs = std::filesystem;

namespace {

struct Scene {
  mesh::FinTemplate fin = mesh::make_caudal_fin({});
  FinSurface surface = make_fin_surface(fin, 4);
  PrescribedKinematics model{KinematicParams{}};
  std::vector<Camera> cams = default_rig({"side", "back", "ventral"}, 0.01, 160, 160);
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

}  // namespace

TEST(Renderer, SameKeySameImageOtherKeyOtherNoise) {
  Scene s;
  const Renderer r(s.surface, {});
  const std::vector<NdArray<double>> sub{s.model.positions(s.surface, 0.01)};
  const auto a = r.render_frame(s.cams[0], sub, noise_key(1, 0, 3));
  const auto b = r.render_frame(s.cams[0], sub, noise_key(1, 0, 3));
  const auto c = r.render_frame(s.cams[0], sub, noise_key(2, 0, 3));
  ASSERT_EQ(a.type(), CV_8U);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(a, c, cv::NORM_L1), 0.0);
  // The noise has the requested spread: a noise-free image differs by about sigma = 2 levels.
  cv::Mat clean8;
  r.render_clean(s.cams[0], sub[0]).convertTo(clean8, CV_8U, 255.0);
  cv::Mat diff;
  cv::subtract(a, clean8, diff, cv::noArray(), CV_64F);
  cv::Scalar mean, sd;
  cv::meanStdDev(diff, mean, sd);
  EXPECT_NEAR(sd[0], 2.0, 0.3);
  EXPECT_NEAR(mean[0], 0.0, 0.2);
}

TEST(Renderer, FinAppearsWhereItProjectsRaysDarker) {
  Scene s;
  RenderOptions o;
  const Renderer r(s.surface, o);
  const auto rest = s.surface.rest;
  const auto& cam = s.cams[0];  // side view: the whole planform
  const auto img = r.render_clean(cam, rest);
  // Far corner: background only.
  EXPECT_NEAR(img.at<float>(2, 2), o.background * (1 - o.vignetting * 0.96), 0.02);
  // Membrane midway between two rays, away from the root, is darker than the background; a point
  // on a thick edge ray is darker still.
  const std::size_t m = s.fin.rays[0].points.size();
  const std::size_t membrane = (8 * 4 + 2) * m + 16;  // between rays 9 and 10, s ~ 2/3
  const std::size_t ray = (0 * 4 + 0) * m + 6;        // on ray 1
  auto at = [&](std::size_t i) {
    const auto p = cam.project({rest(i, 0), rest(i, 1), rest(i, 2)});
    return img.at<float>(static_cast<int>(std::lround(p.y)), static_cast<int>(std::lround(p.x)));
  };
  const double bg = o.background * (1 - o.vignetting * 0.1);
  EXPECT_LT(at(membrane), bg - 0.05);
  EXPECT_LT(at(ray), at(membrane) - 0.1);
  // Coverage matches the projected planform: count pixels clearly off the background and compare
  // with the projected outline's area.
  std::vector<cv::Point2f> poly;
  for (const auto& p : s.fin.outline()) {
    const auto q = cam.project({p[0], 0, p[1]});
    poly.emplace_back(static_cast<float>(q.x), static_cast<float>(q.y));
  }
  const double projected = cv::contourArea(poly);
  cv::Mat bgimg(img.size(), CV_32F);
  const double cx = 0.5 * (img.cols - 1), cy = 0.5 * (img.rows - 1), r2max = cx * cx + cy * cy;
  for (int y = 0; y < img.rows; ++y)
    for (int x = 0; x < img.cols; ++x)
      bgimg.at<float>(y, x) = static_cast<float>(o.background * (1 - o.vignetting * ((x - cx) * (x - cx) + (y - cy) * (y - cy)) / r2max));
  cv::Mat covered = (bgimg - img) > 0.1;
  EXPECT_NEAR(cv::countNonZero(covered) / projected, 1.0, 0.1);
}

TEST(Renderer, MotionBlurSmears) {
  Scene s;
  RenderOptions o;
  o.noise_sigma = 0;
  const Renderer r(s.surface, o);
  const double T = s.model.period();
  const auto sharp = r.render_frame(s.cams[1], {s.model.positions(s.surface, 0)}, 0);
  std::vector<NdArray<double>> sub;
  for (int j = 0; j < 5; ++j) sub.push_back(s.model.positions(s.surface, (j - 2) * 0.01 * T));
  const auto blurred = r.render_frame(s.cams[1], sub, 0);
  // Blur spreads the fin over more pixels at lower contrast.
  const double bg = 255 * o.background * 0.9;
  EXPECT_GT(cv::countNonZero(blurred < bg), cv::countNonZero(sharp < bg));
  double sharp_min, blur_min;
  cv::minMaxLoc(sharp, &sharp_min);
  cv::minMaxLoc(blurred, &blur_min);
  EXPECT_GE(blur_min, sharp_min);
}

TEST(FinSynth, IdenticalRunsGiveIdenticalFiles) {
  const auto dir = fs::temp_directory_path() / ("fin_synth_" + std::to_string(::getpid()));
  auto run = [&](const std::string& sub, int threads) {
    const std::string cmd = std::string(FIN_SYNTH_EXE) + " --out-dir " + (dir / sub).string() +
                            " --periods 0.05 --width 96 --height 96 --supersample 1 --blur-samples 2 --vtk false"
                            " --log-level error --threads " + std::to_string(threads);
    return std::system(cmd.c_str());
  };
  // Same flags twice into the same directory: byte-identical files, truth.h5 included (its
  // provenance records the flags, so it is compared between runs with identical flags).
  ASSERT_EQ(run("a", 2), 0);
  fs::rename(dir / "a", dir / "first");
  ASSERT_EQ(run("a", 2), 0);
  // Another thread count: the images do not depend on how frames are shared among threads.
  ASSERT_EQ(run("b", 1), 0);
  for (const char* f : {"truth.h5", "cameras.yml", "template.json", "frames/side/000000.png", "frames/back/000004.png",
                        "frames/ventral/000002.png"}) {
    ASSERT_TRUE(fs::exists(dir / "a" / f)) << f;
    EXPECT_TRUE(slurp(dir / "a" / f) == slurp(dir / "first" / f)) << f << " differs between identical runs";
    if (std::string(f) != "truth.h5") {
      EXPECT_TRUE(slurp(dir / "a" / f) == slurp(dir / "b" / f)) << f << " depends on the thread count";
    }
  }
  // 0.05 periods of T = 0.2273 s at 500 fps = 5.7 frames, rounded to 6.
  EXPECT_TRUE(fs::exists(dir / "a" / "frames/side/000005.png"));
  EXPECT_FALSE(fs::exists(dir / "a" / "frames/side/000006.png"));
  fs::remove_all(dir);
}
