// Segmentation of footage as labs record it (issue 35, item 3), on synthetic frames made here:
// a fish (body, peduncle, caudal fin) under vignetting, JPEG-compressed, next to a dark strip at
// the image edge larger than the fish, merged with a dark band across the frame, beside debris;
// the noise floor on a frame without visible noise; the peduncle cut of the caudal fin.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "vision/camera.hpp"
#include "vision/fin_separation.hpp"
#include "vision/segmentation.hpp"

using namespace finverse::vision;

namespace {

constexpr int W = 320, H = 120;

struct Fish {
  cv::Mat all, fin;  // CV_8U masks: the whole fish, the caudal fin behind the peduncle
};

// A fish seen from the side, nose to the left: elliptic body, narrow peduncle, spreading fin.
Fish draw_fish(cv::Point2d at, double angle_deg = 0) {
  Fish f{cv::Mat::zeros(H, W, CV_8U), cv::Mat::zeros(H, W, CV_8U)};
  const double a = angle_deg * CV_PI / 180;
  auto P = [&](double x, double y) {
    return cv::Point(static_cast<int>(std::lround(at.x + x * std::cos(a) - y * std::sin(a))),
                     static_cast<int>(std::lround(at.y + x * std::sin(a) + y * std::cos(a))));
  };
  std::vector<cv::Point> body, peduncle, fin;
  for (int i = 0; i < 72; ++i) body.push_back(P(32 * std::cos(i * CV_PI / 36), 13 * std::sin(i * CV_PI / 36)));
  peduncle = {P(26, -4), P(44, -3), P(44, 3), P(26, 4)};
  fin = {P(44, -3), P(66, -22), P(60, 0), P(66, 22), P(44, 3)};
  for (const auto& part : {body, peduncle, fin}) cv::fillPoly(f.all, std::vector<std::vector<cv::Point>>{part}, cv::Scalar(255));
  cv::fillPoly(f.fin, std::vector<std::vector<cv::Point>>{fin}, cv::Scalar(255));
  return f;
}

// The frame: a vignetted backlight, the dark structures (value: darkening factor), noise, JPEG.
cv::Mat render(const std::vector<std::pair<cv::Mat, double>>& dark, unsigned seed, int jpeg_quality = 70) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0, 1.5);
  cv::Mat img(H, W, CV_8U);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const double r2 = (std::pow(x - 0.5 * W, 2) + std::pow(y - 0.5 * H, 2)) / (0.25 * (W * W + H * H));
      double v = 235 * (1 - 0.3 * r2);
      for (const auto& [m, f] : dark)
        if (m.at<std::uint8_t>(y, x)) v *= f;
      img.at<std::uint8_t>(y, x) = cv::saturate_cast<std::uint8_t>(v + noise(rng));
    }
  std::vector<std::uint8_t> buf;
  cv::imencode(".jpg", img, buf, {cv::IMWRITE_JPEG_QUALITY, jpeg_quality});
  return cv::imdecode(buf, cv::IMREAD_GRAYSCALE);
}

double iou(const cv::Mat& a, const cv::Mat& b) { return mask_iou(a, b); }

SegmentationContext context(const cv::Mat& median, const cv::Mat& previous) {
  SegmentationContext c;
  c.median = median, c.previous = previous;
  return c;
}

}  // namespace

TEST(FootageSegmentation, NoiseEstimateHasAFloor) {
  // A saturated, noise-free frame: every neighbour difference is 0.
  cv::Mat frame(H, W, CV_8U, cv::Scalar(255));
  const auto fish = draw_fish({80, 60});
  frame.setTo(120, fish.all);
  const auto seg = segment_fin(frame);
  EXPECT_DOUBLE_EQ(seg.noise_sigma, SegmentationOptions{}.noise_floor);
  EXPECT_GT(iou(seg.mask, fish.all), 0.97);
}

TEST(FootageSegmentation, AVignetteStripLargerThanTheFishIsNotTheFish) {
  const auto fish = draw_fish({90, 60});
  cv::Mat strip = cv::Mat::zeros(H, W, CV_8U);
  strip.colRange(0, 20).setTo(255);  // 20 x 120 px, more than the fish's area
  ASSERT_GT(cv::countNonZero(strip), cv::countNonZero(fish.all));
  const cv::Mat frame = render({{fish.all, 0.55}, {strip, 0.6}}, 1);
  const auto seg = segment_fin(frame);
  EXPECT_GT(iou(seg.mask, fish.all), 0.9);
  EXPECT_FALSE(seg.touches_border);
  EXPECT_GE(seg.rejected_blobs, 1);
  // Keeping border blobs takes the strip (the behaviour before).
  SegmentationOptions keep;
  keep.reject_border = false;
  EXPECT_LT(iou(segment_fin(frame, keep).mask, fish.all), 0.1);
}

TEST(FootageSegmentation, ADarkBandMergedWithTheFishGoesWithTheTemporalMedian) {
  // A band across the frame that the swimming fish overlaps; 28 frames, 8 px per frame (the
  // fish covers a pixel in at most 13 of them, so the median is the background).
  cv::Mat band = cv::Mat::zeros(H, W, CV_8U);
  band.rowRange(70, 84).setTo(255);
  std::vector<cv::Mat> frames;
  std::vector<Fish> fish;
  for (int k = 0; k < 28; ++k) {
    fish.push_back(draw_fish({36.0 + 8 * k, 60}));
    frames.push_back(render({{fish.back().all, 0.55}, {band, 0.6}}, 10 + k));
  }
  const cv::Mat median = temporal_median(frames);
  double worst_with = 1, best_without = 0;
  cv::Mat previous;
  for (std::size_t k = 0; k < frames.size(); k += 5) {
    const auto with = segment_fin(frames[k], {}, context(median, previous));
    worst_with = std::min(worst_with, iou(with.mask, fish[k].all));
    best_without = std::max(best_without, iou(segment_fin(frames[k]).mask, fish[k].all));
  }
  EXPECT_GT(worst_with, 0.85);
  EXPECT_LT(best_without, 0.6);  // the band and the fish are one blob
  // The median everywhere works too.
  SegmentationOptions med;
  med.background = BackgroundModel::median;
  EXPECT_GT(iou(segment_fin(frames[7], med, context(median, {})).mask, fish[7].all), 0.85);
}

TEST(FootageSegmentation, TheFishIsTheBlobConnectedToThePreviousFrames) {
  const auto fish = draw_fish({60, 60});
  cv::Mat debris = cv::Mat::zeros(H, W, CV_8U);
  cv::circle(debris, {200, 60}, 28, cv::Scalar(255), cv::FILLED);  // larger than the fish
  ASSERT_GT(cv::countNonZero(debris), cv::countNonZero(fish.all));
  const cv::Mat frame = render({{fish.all, 0.55}, {debris, 0.5}}, 3);
  EXPECT_LT(iou(segment_fin(frame).mask, fish.all), 0.1);  // alone, the larger blob wins
  const auto prev = draw_fish({57, 61}).all;
  const auto seg = segment_fin(frame, {}, context({}, prev));
  EXPECT_GT(iou(seg.mask, fish.all), 0.9);
  EXPECT_FALSE(seg.lost);
  // A previous fish far from every blob: lost, nothing segmented.
  cv::Mat far = cv::Mat::zeros(H, W, CV_8U);
  cv::circle(far, {110, 10}, 4, cv::Scalar(255), cv::FILLED);
  const auto gone = segment_fin(frame, {}, context({}, far));
  EXPECT_TRUE(gone.lost);
  EXPECT_EQ(cv::countNonZero(gone.mask), 0);
}

TEST(FootageSegmentation, TheCaudalFinIsCutAtThePeduncle) {
  for (double angle : {0.0, 30.0, 180.0}) {
    const auto fish = draw_fish({100, 60}, angle);
    const auto cut = separate_caudal_fin(fish.all);
    ASSERT_TRUE(cut.cut) << angle;
    EXPECT_GT(iou(cut.fin, fish.fin), 0.85) << angle;
    EXPECT_GT(cut.body_px, 2 * cut.peduncle_px) << angle;
    // Through the segmentation of a compressed frame.
    SegmentationOptions o;
    o.fin_cut = true;
    const auto seg = segment_fin(render({{fish.all, 0.55}}, 5), o);
    EXPECT_TRUE(seg.fin_cut);
    EXPECT_GT(iou(seg.mask, fish.fin), 0.8) << angle;
  }
  // A fin alone (spreading from its root, no body): nothing to cut.
  const auto fin_only = draw_fish({100, 60}).fin;
  EXPECT_FALSE(separate_caudal_fin(fin_only).cut);
  EXPECT_EQ(cv::countNonZero(separate_caudal_fin(fin_only).fin != fin_only), 0);
  // A tapering body without a fin: nothing to cut either.
  cv::Mat spindle = cv::Mat::zeros(H, W, CV_8U);
  cv::ellipse(spindle, {100, 60}, {50, 12}, 0, 0, 360, cv::Scalar(255), cv::FILLED);
  EXPECT_FALSE(separate_caudal_fin(spindle).cut);
  // With a calibration: the body cut at the projected root plane x = 0 (fin upstream end at x = 0,
  // the body at x < 0). The side view sees the plane as a line; a view from behind cannot.
  {
    const auto side = look_at("side", W, H, 400, {0.005, -0.1, 0}, {0.005, 0, 0}, {0, 0, 1});
    const auto back = look_at("back", W, H, 400, {0.1, 0, 0}, {0, 0, 0}, {0, 0, 1});
    cv::Vec3d line;
    EXPECT_FALSE(root_plane_line(back, 0.01, line));
    ASSERT_TRUE(root_plane_line(side, 0.01, line));
    const auto root = side.project({-0.0002, 0, 0});  // a fiftieth of the chord upstream
    EXPECT_NEAR(line[0] * root.x + line[1] * root.y + line[2], 0, 1e-9);
    const auto fin_point = side.project({0.005, 0, 0.002}), body_point = side.project({-0.005, 0, 0});
    EXPECT_GT(line[0] * fin_point.x + line[1] * fin_point.y + line[2], 0);
    EXPECT_LT(line[0] * body_point.x + line[1] * body_point.y + line[2], 0);
    cv::Mat all = cv::Mat::zeros(H, W, CV_8U);
    all.setTo(255);
    const int kept = cv::countNonZero(fin_side_mask(all, line));
    EXPECT_NEAR(kept, (W - root.x) * H, 2 * H);  // the columns right of the root
  }
  // The user's rectangle.
  const auto fish = draw_fish({100, 60});
  const auto region = fin_region_mask(fish.all, cv::Rect(145, 0, 55, H));
  EXPECT_GT(iou(region, fish.fin), 0.85);
}

TEST(FootageSegmentation, TheOpaqueBodyBehindAnEdgeOnFinIsMarked) {
  // From behind: the body's opaque cross-section, and in front of it the fin edge-on, a
  // translucent band 3 px wide reaching past the body, its rays dark dots along it.
  cv::Mat body = cv::Mat::zeros(H, W, CV_8U), fin = cv::Mat::zeros(H, W, CV_8U), rays = cv::Mat::zeros(H, W, CV_8U);
  cv::ellipse(body, {160, 60}, {20, 32}, 0, 0, 360, cv::Scalar(255), cv::FILLED);
  fin(cv::Rect(158, 6, 3, 108)).setTo(255);
  for (int y = 10; y < 112; y += 10) rays(cv::Rect(158, y, 3, 3)).setTo(255);
  const cv::Mat frame = render({{body, 0.25}, {fin, 0.6}, {rays, 0.3}}, 7);
  SegmentationContext ctx;
  ctx.find_body = true;
  const auto seg = segment_fin(frame, {}, ctx);
  ASSERT_FALSE(seg.body.empty());
  EXPECT_GT(cv::countNonZero(seg.body & body), 0.97 * cv::countNonZero(body));
  // The fin beyond the body (and its rays there) is not taken for body.
  cv::Mat near_body;
  cv::dilate(body, near_body, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(9, 9)));
  EXPECT_EQ(cv::countNonZero(seg.body & fin & (near_body == 0)), 0);
  EXPECT_LT(iou(seg.mask, fin), 0.3);               // the blob is mostly body
  EXPECT_GT(mask_iou(seg.mask, fin, seg.body), 0.85);  // outside the body it is the fin
  // Without the request, no body mask; a translucent fish has no opaque part to mark.
  EXPECT_TRUE(segment_fin(frame).body.empty());
  EXPECT_TRUE(segment_fin(render({{body, 0.6}}, 8), {}, ctx).body.empty());
}

TEST(FootageSegmentation, AStaticBodyTakesOnlyItsSideOfTheRootLineIntoTheBackground) {
  // Side view: a body held still at the left border, the fin's root beside it just as still,
  // the rest of the fin beating; the root plane at x = 100, the fin to the right of it.
  cv::Mat body = cv::Mat::zeros(H, W, CV_8U), root = cv::Mat::zeros(H, W, CV_8U);
  body(cv::Rect(0, 45, 100, 30)).setTo(255);
  root(cv::Rect(100, 40, 30, 40)).setTo(255);
  std::vector<cv::Mat> frames, tails;
  for (int k = 0; k < 24; ++k) {
    cv::Mat tail = cv::Mat::zeros(H, W, CV_8U);
    cv::ellipse(tail, {150, static_cast<int>(60 + 30 * std::sin(0.5 * k))}, {22, 12}, 0, 0, 360, cv::Scalar(255), cv::FILLED);
    tail(cv::Rect(128, 0, 2, H)).setTo(0);
    cv::line(tail, {128, 60}, {150, static_cast<int>(60 + 30 * std::sin(0.5 * k))}, cv::Scalar(255), 9);
    tails.push_back(tail);
    frames.push_back(render({{body, 0.3}, {root, 0.55}, {tail, 0.55}}, 20 + k));
  }
  const cv::Mat background = temporal_median(frames, kStaticQuantile);
  SegmentationContext ctx;
  ctx.median = background;
  ctx.cut_at_line = true;
  ctx.root_line = {1, 0, -100};
  const int k = 5;
  const cv::Mat fin = (root | tails[k]) & fin_side_mask(cv::Mat(H, W, CV_8U, cv::Scalar(255)), ctx.root_line);
  EXPECT_GT(iou(segment_fin(frames[k], {}, ctx).mask, fin), 0.85);
  // Taking the whole static structure from the percentile background loses the fin's root.
  SegmentationContext whole;
  whole.median = background;
  const cv::Mat without = fin_side_mask(segment_fin(frames[k], {}, whole).mask, ctx.root_line);
  EXPECT_LT(cv::countNonZero(without & root), 0.5 * cv::countNonZero(root));
}

TEST(FootageSegmentation, ThePeduncleCutKeepsTheEndBeyondTheRootPlane) {
  // The image border cuts the body short, so it has less area than the fin.
  cv::Mat all = cv::Mat::zeros(H, W, CV_8U), fin = cv::Mat::zeros(H, W, CV_8U);
  all(cv::Rect(0, 45, 30, 30)).setTo(255);
  all(cv::Rect(30, 56, 20, 8)).setTo(255);
  const std::vector<cv::Point> fan{{50, 56}, {110, 20}, {110, 100}, {50, 64}};
  cv::fillPoly(fin, std::vector<std::vector<cv::Point>>{fan}, cv::Scalar(255));
  all |= fin;
  ASSERT_LT(cv::countNonZero(all(cv::Rect(0, 0, 30, H))), cv::countNonZero(fin));
  EXPECT_LT(iou(separate_caudal_fin(all).fin, fin), 0.5);  // by area: the body is taken for the fin
  const cv::Vec3d line{1, 0, -50};
  const auto cut = separate_caudal_fin(all, {}, &line);
  ASSERT_TRUE(cut.cut);
  EXPECT_GT(iou(cut.fin, fin), 0.9);
  EXPECT_GT(cut.tailward.x, 0.9);
}
