// The 2-D mode's centreline on deep-bodied fish (issue 47): a body half as wide as it is long with
// a blunt head, drawn here from above with pectoral fins that stick out of its silhouette, on
// one flank or on both; the centreline must stay on the drawn axis where the silhouette's own
// middle is pulled towards the fins. And fin-track midline's refusals: a clip with no fish, a fish
// that fills the frame (exit 2), and a clip in which most frames show the fish cut by the border
// (exit 1, the count and the reason).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "vision/fish_centreline.hpp"
#include "vision/midline.hpp"

using namespace finverse::vision;

namespace {

constexpr int kScale = 4;  // drawn at 4 samples per pixel, then cut at half cover

// A deep fish seen from above on the line y = yc: body from the snout at x = x0 over `length` px,
// half-width `half_width` at 40 % of it (an elliptic, blunt head), tapering to a 4 px peduncle, and
// a caudal fin 30 px long and 3 px wide behind it; pectoral fans hinged at 30 % of the body on
// the flanks, `right` and `left` degrees open (0: none), 0.6 half-widths long.
struct DeepFish {
  double x0 = 30, yc = 100, length = 200, half_width = 50;
  double right = 70, left = 0;

  double body_half_width(double u) const {
    if (u <= 0.4) return half_width * std::sqrt(std::max(0.0, 1 - std::pow((0.4 - u) / 0.4, 2)));
    return 2 + (half_width - 2) * 0.5 * (1 + std::cos(std::numbers::pi * (u - 0.4) / 0.6));
  }
  void fan(cv::Mat& big, double side, double open_deg) const {
    if (open_deg <= 0) return;
    const double u = 0.3, hx = x0 + u * length, hy = yc + side * 0.85 * body_half_width(u), r = 0.6 * half_width;
    std::vector<cv::Point> p{cv::Point(static_cast<int>(hx * kScale), static_cast<int>(hy * kScale))};
    for (int j = 0; j <= 12; ++j) {
      const double phi = (10 + (open_deg - 10) * j / 12.0) * std::numbers::pi / 180;
      p.emplace_back(static_cast<int>((hx + r * std::cos(phi)) * kScale),
                     static_cast<int>((hy + side * r * std::sin(phi)) * kScale));
    }
    cv::fillPoly(big, std::vector<std::vector<cv::Point>>{p}, cv::Scalar(255));
  }
  cv::Mat mask(int width = 300, int height = 200) const {
    cv::Mat big = cv::Mat::zeros(height * kScale, width * kScale, CV_8U);
    std::vector<cv::Point> outline;
    for (int k = 0; k <= 400; ++k) {
      const double u = k / 400.0;
      outline.emplace_back(static_cast<int>((x0 + u * length) * kScale),
                           static_cast<int>((yc - body_half_width(u)) * kScale));
    }
    for (int k = 400; k >= 0; --k) {
      const double u = k / 400.0;
      outline.emplace_back(static_cast<int>((x0 + u * length) * kScale),
                           static_cast<int>((yc + body_half_width(u)) * kScale));
    }
    cv::fillPoly(big, std::vector<std::vector<cv::Point>>{outline}, cv::Scalar(255));
    cv::rectangle(big, cv::Point(static_cast<int>((x0 + length - 2) * kScale), static_cast<int>((yc - 1.5) * kScale)),
                  cv::Point(static_cast<int>((x0 + length + 30) * kScale), static_cast<int>((yc + 1.5) * kScale)),
                  cv::Scalar(255), cv::FILLED);
    fan(big, 1, right);
    fan(big, -1, left);
    cv::Mat m;
    cv::resize(big, m, cv::Size(width, height), 0, 0, cv::INTER_AREA);
    return m > 127;
  }
  // The centreline on the drawn axis (x increasing from the snout), and the largest distance of its
  // stations from y = yc, over the body (the caudal fin's 3 px are the silhouette's own middle).
  double worst_offset(const cv::Mat& m, int stations = 25) const {
    std::vector<cv::Point> pts;
    cv::findNonZero(m, pts);
    double lo = 1e300, hi = -1e300;
    for (const auto& p : pts) lo = std::min(lo, double(p.x)), hi = std::max(hi, double(p.x));
    const auto line = fish_centreline(m, body_core(m), cv::Point2d(0, 0), cv::Point2d(1, 0), lo, hi, stations);
    double worst = 0;
    for (const auto& p : line) {
      EXPECT_FALSE(std::isnan(p.x));
      worst = std::max(worst, std::abs(p.y - yc));
    }
    return worst;
  }
};

// The silhouette's own middle across x = `x` (the naive midline), minus yc.
double naive_offset(const cv::Mat& m, int x, double yc) {
  int top = -1, bottom = -1;
  for (int y = 0; y < m.rows; ++y)
    if (m.at<std::uint8_t>(y, x)) bottom = y, top = top < 0 ? y : top;
  return 0.5 * (top + bottom) - yc;
}

}  // namespace

TEST(FishCentreline, ADeepBodyWithAFinOnOneFlankKeepsItsAxis) {
  const DeepFish fish;
  const cv::Mat m = fish.mask();
  // Through the fin's base the silhouette's middle is pulled 9 px towards the fin.
  EXPECT_GT(std::abs(naive_offset(m, static_cast<int>(fish.x0 + 0.36 * fish.length), fish.yc)), 8.0);
  EXPECT_LT(fish.worst_offset(m), 0.75);
}

TEST(FishCentreline, FinsOpenedUnequallyOnBothFlanks) {
  DeepFish fish;
  fish.left = 35;
  const cv::Mat m = fish.mask();
  EXPECT_GT(std::abs(naive_offset(m, static_cast<int>(fish.x0 + 0.36 * fish.length), fish.yc)), 4.0);
  EXPECT_LT(fish.worst_offset(m), 1.0);
}

TEST(FishCentreline, TheCoreLeavesTheFinsOutAndKeepsTheBluntHead) {
  const DeepFish fish;
  const cv::Mat m = fish.mask();
  const auto core = body_core(m);
  EXPECT_NEAR(core.half_width, fish.half_width, 1.5);
  // No core pixel more than a few px beyond the flank under the fin's tip; the head's front kept.
  const double tip_x = fish.x0 + 0.3 * fish.length + 0.6 * fish.half_width * std::cos(70 * std::numbers::pi / 180);
  const int x = static_cast<int>(tip_x);
  int lowest = 0;
  for (int y = 0; y < m.rows; ++y)
    if (core.mask.at<std::uint8_t>(y, x)) lowest = y;
  EXPECT_LT(lowest - (fish.yc + fish.body_half_width((x - fish.x0) / fish.length)), 8.0);
  EXPECT_GT(core.mask.at<std::uint8_t>(static_cast<int>(fish.yc), static_cast<int>(fish.x0 + 2)), 0);
}

#ifdef FIN_TRACK_EXE
namespace {

struct Clip {
  std::filesystem::path dir;
  explicit Clip(const std::string& name)
      : dir(std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir / "frames");
  }
  ~Clip() { std::filesystem::remove_all(dir); }
  void frame(int k, const cv::Mat& fish_mask) const {
    cv::Mat img(fish_mask.size(), CV_8U, cv::Scalar(215));
    img.setTo(60, fish_mask);
    char name[32];
    std::snprintf(name, sizeof name, "%06d.png", k);
    cv::imwrite((dir / "frames" / name).string(), img);
  }
  // fin-track midline's exit status and its standard error.
  int run(std::string& err) const {
    const std::string cmd = std::string(FIN_TRACK_EXE) + " --log-level warn midline --frames " +
                            (dir / "frames").string() + " --fps 100 --out " + (dir / "m.h5").string() + " 2> " +
                            (dir / "err").string();
    const int rc = std::system(cmd.c_str());
    std::ifstream in(dir / "err");
    err.assign(std::istreambuf_iterator<char>(in), {});
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  }
};

int line_count(const std::string& s) { return static_cast<int>(std::count(s.begin(), s.end(), '\n')); }

}  // namespace

TEST(FinTrackMidline, AClipWithoutAFishOrFilledByItIsRefused) {
  std::string err;
  {
    const Clip clip("midline_no_fish");
    for (int k = 0; k < 12; ++k) clip.frame(k, cv::Mat::zeros(200, 300, CV_8U));
    EXPECT_EQ(clip.run(err), 2) << err;
    EXPECT_EQ(line_count(err), 1) << err;
    EXPECT_NE(err.find("no fish found in any of the 12 frames"), std::string::npos) << err;
    EXPECT_FALSE(std::filesystem::exists(clip.dir / "m.h5"));
  }
  {
    const Clip clip("midline_fills");
    DeepFish big;
    big.x0 = -40, big.length = 400, big.half_width = 120;
    for (int k = 0; k < 12; ++k) clip.frame(k, big.mask());
    EXPECT_EQ(clip.run(err), 2) << err;
    EXPECT_EQ(line_count(err), 1) << err;
    EXPECT_NE(err.find("fills the frame"), std::string::npos) << err;
  }
}

TEST(FinTrackMidline, MostFramesCutByTheBorderExitOneWithTheReason) {
  const Clip clip("midline_border");
  for (int k = 0; k < 16; ++k) {
    DeepFish fish;
    fish.x0 = k < 10 ? -20 : 30;  // the snout outside the frame in 10 of the 16
    fish.right = 20 + 4 * k;
    clip.frame(k, fish.mask());
  }
  std::string err;
  EXPECT_EQ(clip.run(err), 1) << err;
  EXPECT_NE(err.find("10 of 16 frames could not be measured, most often because the fish touches the image border"),
            std::string::npos)
      << err;
  EXPECT_TRUE(std::filesystem::exists(clip.dir / "m.h5"));  // written, flagged
}
#endif
