// Realistic virtual footage (issue 35, item 8): the fish's body is drawn opaque upstream of the
// fin's root and moves with it, the renderer's split into exposure and sensor gives render_frame's
// image, gain saturates, debris is seeded, JPEG compression is mild, and fin-synth's footage flags
// are deterministic and refuse bad values with one line and exit 2.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <unistd.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/error.hpp"
#include "vision/fish_body.hpp"
#include "vision/footage_effects.hpp"
#include "vision/kinematic_model.hpp"
#include "vision/renderer.hpp"
#include "vision/video_clip.hpp"

using namespace finverse;
using namespace finverse::vision;
namespace fs = std::filesystem;

namespace {

struct FootageScene {
  mesh::FinTemplate fin = mesh::make_caudal_fin({});
  FinSurface surface = make_fin_surface(fin, 2);
  PrescribedKinematics model{KinematicParams{}};
  std::vector<Camera> cams = default_rig({"side", "back"}, 0.01, 96, 96);
};

double level_at(const cv::Mat& img, const Camera& cam, const cv::Vec3d& world) {
  const auto p = cam.project(world);
  return img.at<float>(static_cast<int>(std::lround(p.y)), static_cast<int>(std::lround(p.x)));
}

std::string slurp_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

}  // namespace

TEST(FishBody, DrawnUpstreamOfTheRootAndMovesWithIt) {
  FootageScene s;
  const FishBody body(s.surface, {});
  RenderOptions o;
  o.supersample = 1;
  const Renderer plain(s.surface, o), with_body(s.surface, o, &body);
  const auto rest = s.surface.rest;
  const auto& side = s.cams[0];
  const cv::Mat a = plain.render_clean(side, rest), b = with_body.render_clean(side, rest);
  const double c = s.surface.chord;
  // Half a chord upstream of the root on the axis: background without the body, body with it.
  EXPECT_GT(level_at(a, side, {-0.5 * c, 0, 0}), 0.7);
  EXPECT_LT(level_at(b, side, {-0.5 * c, 0, 0}), 0.25);
  // Downstream of the root (mid-fin) the side view is unchanged: the body hides nothing there.
  EXPECT_FLOAT_EQ(level_at(b, side, {0.5 * c, 0, 0}), level_at(a, side, {0.5 * c, 0, 0}));
  // The fin's root moved by 0.3 c along y and 0.1 c along x: the peduncle's end (the last vertex)
  // follows it exactly, the snout (the first) a tenth across and fully along, each vertex between.
  auto moved = rest;
  for (std::size_t i = 0; i < moved.dim(0); ++i) moved(i, 1) += 0.3 * c, moved(i, 0) += 0.1 * c;
  const auto p0 = body.place(rest), p1 = body.place(moved);
  const std::size_t last = p0.dim(0) - 1;
  EXPECT_NEAR(p1(last, 1) - p0(last, 1), 0.3 * c, 1e-12);
  EXPECT_NEAR(p1(0, 1) - p0(0, 1), 0.03 * c, 1e-12);
  for (std::size_t v = 0; v <= last; v += 97) {
    EXPECT_NEAR(p1(v, 0) - p0(v, 0), 0.1 * c, 1e-12);
    EXPECT_GE(p1(v, 1) - p0(v, 1), 0.03 * c - 1e-12);
    EXPECT_LE(p1(v, 1) - p0(v, 1), 0.3 * c + 1e-12);
  }
  // From behind, the fin is in front of the body: the body only darkens the image, and some pixels
  // show the translucent fin over it (lighter than the bare body, darker than fin over background).
  const auto& back = s.cams[1];
  const cv::Mat fin_only = plain.render_clean(back, rest), both = with_body.render_clean(back, rest);
  EXPECT_LE(cv::norm(cv::max(both - fin_only, 0.0), cv::NORM_INF), 1e-6);
  const cv::Mat fin_over_body = (both > FishBodyOptions{}.level + 0.02) & (both < fin_only - 0.05);
  EXPECT_GT(cv::countNonZero(fin_over_body), 0);
  EXPECT_LT(level_at(both, back, {-c, 0.08 * c, 0}), 0.25);  // bare body beside the fin's edge-on strip
  EXPECT_THROW(FishBody(s.surface, FishBodyOptions{.length = -1}), Error);
}

TEST(FootageRender, ExposureAndSensorAreRenderFrameAndGainSaturates) {
  FootageScene s;
  RenderOptions o;
  o.supersample = 1;
  const Renderer r(s.surface, o);
  const std::vector<NdArray<double>> sub{s.model.positions(s.surface, 0.01)};
  const cv::Mat frame = r.render_frame(s.cams[0], sub, noise_key(1, 0, 0));
  const cv::Mat split = r.sensor(r.render_exposure(s.cams[0], sub), noise_key(1, 0, 0));
  EXPECT_EQ(cv::norm(frame, split, cv::NORM_INF), 0.0);
  o.gain = 1.4;
  const Renderer bright(s.surface, o);
  const cv::Mat sat = bright.render_frame(s.cams[0], sub, noise_key(1, 0, 0));
  EXPECT_EQ(sat.at<std::uint8_t>(48, 90), 255);  // background at the image centre row clips
  o.gain = 0;
  EXPECT_THROW(Renderer(s.surface, o), Error);
}

TEST(FootageEffects, DebrisSeededAndJpegMild) {
  const cv::Mat flat(64, 80, CV_32F, cv::Scalar(0.9));
  auto specks = [&](std::uint64_t seed, double t) {
    cv::Mat img = flat.clone();
    Debris({.count = 12}, seed, 0, 80, 64).draw(img, t);
    return img;
  };
  EXPECT_EQ(cv::norm(specks(3, 0.1), specks(3, 0.1), cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(specks(3, 0.1), specks(4, 0.1), cv::NORM_INF), 0.1);
  EXPECT_GT(cv::norm(specks(3, 0.0), specks(3, 0.05), cv::NORM_INF), 0.1);  // drifting specks moved
  double lo;
  cv::minMaxLoc(specks(3, 0), &lo);
  EXPECT_LT(lo, 0.6);
  cv::Mat none = flat.clone();
  Debris({}, 3, 0, 80, 64).draw(none, 0);
  EXPECT_EQ(cv::norm(none, flat, cv::NORM_INF), 0.0);
  EXPECT_THROW(Debris({.count = -1}, 3, 0, 80, 64), Error);

  cv::Mat grey(64, 64, CV_8U);
  cv::randu(grey, 100, 140);
  const cv::Mat j = jpeg_round_trip(grey, 75);
  EXPECT_GT(cv::norm(grey, j, cv::NORM_INF), 0.0);
  EXPECT_LT(cv::norm(grey, j, cv::NORM_L1) / grey.total(), 12.0);
  EXPECT_THROW(jpeg_round_trip(grey, 0), Error);
}

TEST(FootageEffects, MjpgAviReadsBackFrameForFrame) {
  const auto avi = fs::temp_directory_path() / ("footage_" + std::to_string(::getpid()) + ".avi");
  std::vector<cv::Mat> frames;
  for (int k = 0; k < 4; ++k) {
    cv::Mat f(48, 64, CV_8U, cv::Scalar(200));
    cv::circle(f, {16 + 8 * k, 24}, 6, cv::Scalar(40), -1);
    frames.push_back(f);
  }
  write_mjpg_avi(avi, frames, 250, 90);
  const VideoClip clip(avi);
  ASSERT_EQ(clip.frames(), 4);
  EXPECT_NEAR(clip.fps(), 250, 1e-6);
  for (int k = 0; k < 4; ++k) EXPECT_LT(cv::norm(clip.grey(k), frames[k], cv::NORM_L1) / frames[k].total(), 3.0) << k;
  fs::remove(avi);
}

TEST(FinSynth, RealisticFootageDeterministicAndBadFlagsExit2) {
  const auto dir = fs::temp_directory_path() / ("fin_synth_footage_" + std::to_string(::getpid()));
  auto run = [&](const std::string& sub, const std::string& flags) {
    const std::string cmd = std::string(FIN_SYNTH_EXE) + " --out-dir " + (dir / sub).string() +
                            " --periods 0.02 --width 64 --height 64 --supersample 1 --views side --vtk false"
                            " --log-level error " + flags + " 2> " + (dir / (sub + ".err")).string();
    fs::create_directories(dir);
    const int rc = std::system(cmd.c_str());
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  };
  // Same flags, other thread counts: the same frames (the clean default's are tested in test_renderer).
  ASSERT_EQ(run("a", "--footage realistic --threads 2"), 0);
  ASSERT_EQ(run("b", "--footage realistic --threads 1"), 0);
  const char* f = "frames/side/000001.png";
  EXPECT_TRUE(slurp_file(dir / "a" / f) == slurp_file(dir / "b" / f));
  for (const char* bad : {"--jpeg-quality 101", "--body-length 2", "--footage realistic --gain -1",
                          "--footage realistic --debris -3", "--field-chords 0"}) {
    EXPECT_EQ(run("bad", bad), 2) << bad;
    const auto err = slurp_file(dir / "bad.err");
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << bad << ": " << err;
  }
  fs::remove_all(dir);
}
