// The 2-D single-view mode (issue 35, item 4) on a synthetic swimming fish drawn here: a body
// wave y = A(xi) sin(2 pi (xi L / lambda - f t)) along a tapering body, seen from above; the tail
// tip, the tail-beat frequency, amplitude and body wavelength against the drawn ones; and
// `fin-track midline` on the swimmer as an MJPG AVI: its HDF5, CSV and overlay video.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <numbers>
#include <vector>

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "core/hdf5_file.hpp"

#include "vision/midline.hpp"

using namespace finverse::vision;

namespace {

struct Swimmer {
  double L = 140, x0 = 40, yc = 80, lambda = 150, f = 5, fps = 100, a_tail = 14;
  double amplitude(double xi) const { return a_tail * (0.15 + 0.85 * xi * xi); }
  double y(double xi, double t) const {
    return yc + amplitude(xi) * std::sin(2 * std::numbers::pi * (xi * L / lambda - f * t));
  }
  // The fish at time t: overlapping discs along the midline, 10 px half-width tapering to 1.
  cv::Mat mask(double t, int scale = 4) const {
    cv::Mat big = cv::Mat::zeros(160 * scale, 240 * scale, CV_8U);
    for (double xi = 0; xi <= 1.0; xi += 0.002) {
      const double r = 1 + 9 * std::sin(std::numbers::pi * std::pow(std::min(xi / 0.95, 1.0), 0.5) * 0.999 + 1e-3) * (1 - 0.9 * xi);
      cv::circle(big, cv::Point(static_cast<int>((x0 + xi * L) * scale), static_cast<int>(y(xi, t) * scale)),
                 static_cast<int>(r * scale), cv::Scalar(255), cv::FILLED);
    }
    cv::Mat m;
    cv::resize(big, m, cv::Size(240, 160), 0, 0, cv::INTER_AREA);  // area coverage, then half-cover threshold
    return m > 127;
  }
};

}  // namespace

TEST(Midline, TailTipFrequencyAmplitudeAndWavelengthOfASwimmer) {
  const Swimmer s;
  std::vector<cv::Mat> masks;
  const int nf = 64;  // 3.2 beats
  for (int k = 0; k < nf; ++k) masks.push_back(s.mask(k / s.fps));
  cv::Point2d axis;
  const auto m = extract_midlines(masks, 25, &axis);
  EXPECT_GT(axis.x, 0.99);  // head (left, the wider end) to tail
  // Tail tip: on the drawn tip (its 1 px disc's far end) to within a pixel across.
  double worst = 0;
  for (int k = 0; k < nf; ++k) {
    ASSERT_TRUE(m[k].valid);
    worst = std::max(worst, std::abs(m[k].tip.y - s.y(1.0, k / s.fps)));
  }
  EXPECT_LT(worst, 1.0);
  const auto beat = tail_beat(m, axis, s.fps);
  EXPECT_NEAR(beat.frequency_hz, s.f, 0.01 * s.f);
  EXPECT_NEAR(beat.amplitude_px, s.a_tail, 0.05 * s.a_tail);
  EXPECT_NEAR(beat.wavelength_px, s.lambda, 0.1 * s.lambda);
  EXPECT_EQ(beat.beats, 3);
}

TEST(Midline, AFrameThatLostTheFinIsNotMeasured) {
  const Swimmer s;
  std::vector<cv::Mat> masks;
  const int nf = 64;
  for (int k = 0; k < nf; ++k) masks.push_back(s.mask(k / s.fps));
  // Frame 10: the tail's last fifth missing from the mask (too faint to segment).
  masks[10].colRange(static_cast<int>(s.x0 + 0.8 * s.L), masks[10].cols).setTo(0);
  cv::Point2d axis;
  const auto m = extract_midlines(masks, 25, &axis);
  EXPECT_FALSE(m[10].valid);
  EXPECT_TRUE(m[10].lost_fin);
  for (int k = 0; k < nf; ++k)
    if (k != 10) {
      EXPECT_TRUE(m[k].valid) << k;
    }
  const auto beat = tail_beat(m, axis, s.fps);
  EXPECT_TRUE(std::isnan(beat.tip_lateral_px[10]));
  EXPECT_NEAR(beat.amplitude_px, s.a_tail, 0.05 * s.a_tail);
}

// A fish that turns: a slender body (an ellipse 100 x 16 px) with a 40 px tail, its heading
// swinging from -35 to +35 degrees over the record about its centre. Its extent on the record's
// mean axis shrinks by up to 18 %; along its own midline it keeps its length, so every frame is
// valid (issue 47: the length rule once dropped such frames as "the fin lost").
TEST(Midline, AFishThatTurnsKeepsItsLengthAndStaysValid) {
  std::vector<cv::Mat> masks;
  const int nf = 24, scale = 4;
  for (int k = 0; k < nf; ++k) {
    const double a = (-35 + 70.0 * k / (nf - 1)) * std::numbers::pi / 180;
    const cv::Point2d c(120, 120), u(std::cos(a), std::sin(a));
    cv::Mat big = cv::Mat::zeros(240 * scale, 240 * scale, CV_8U);
    cv::ellipse(big, cv::Point(static_cast<int>(c.x * scale), static_cast<int>(c.y * scale)),
                cv::Size(50 * scale, 8 * scale), a * 180 / std::numbers::pi, 0, 360, cv::Scalar(255), cv::FILLED);
    const cv::Point2d t0 = c + 48.0 * u, t1 = c + 88.0 * u;
    cv::line(big, cv::Point(static_cast<int>(t0.x * scale), static_cast<int>(t0.y * scale)),
             cv::Point(static_cast<int>(t1.x * scale), static_cast<int>(t1.y * scale)), cv::Scalar(255), 3 * scale);
    cv::Mat m;
    cv::resize(big, m, cv::Size(240, 240), 0, 0, cv::INTER_AREA);
    masks.push_back(m > 127);
  }
  cv::Point2d axis;
  const auto m = extract_midlines(masks, 25, &axis);
  for (int k = 0; k < nf; ++k) EXPECT_TRUE(m[k].valid) << k << ": " << m[k].reason;
}

// A forked tail drawn here at 1/16 px and blurred (sigma 1 px) as a camera does: two lobes with
// square ends at x = 52.3 (upper, y 23-27.4) and 49.6 (lower), 40 levels dark. A mask from a
// threshold above half the fin's contrast (a faint fin in noise) ends a pixel short; the tip read
// from the image along the axis, where the darkening falls to half the lobe's, is the upper lobe's
// end to 0.4 px (0.35 blur sigmas: the lobe's level is read within 2 px behind where the fin is
// last detected, a little past the edge), and across on that lobe's end.
TEST(Midline, TheTailTipOfABlurredLobeToSubPixel) {
  const int scale = 16, W = 70, H = 60;
  const double end_x = 52.3;
  cv::Mat big = cv::Mat::zeros(H * scale, W * scale, CV_8U);
  const auto box = [&](double x0, double y0, double x1, double y1) {  // pixel centres at integers
    cv::rectangle(big, cv::Point(static_cast<int>(std::lround((x0 + 0.5) * scale)), static_cast<int>(std::lround((y0 + 0.5) * scale))),
                  cv::Point(static_cast<int>(std::lround((x1 + 0.5) * scale)) - 1, static_cast<int>(std::lround((y1 + 0.5) * scale)) - 1),
                  cv::Scalar(255), cv::FILLED);
  };
  box(5, 22, 35, 38);        // the peduncle
  box(35, 23, end_x, 27.4);  // upper lobe
  box(35, 32, 49.6, 37);     // lower lobe, 2.7 px shorter
  cv::Mat cover;
  cv::resize(big, cover, cv::Size(W, H), 0, 0, cv::INTER_AREA);
  cover.convertTo(cover, CV_32F, 1.0 / 255);
  cv::GaussianBlur(cover, cover, cv::Size(0, 0), 1.0);
  TipEvidence e;
  e.darkening = 40 * cover;
  e.threshold = 6;
  const cv::Mat mask = e.darkening > 32;  // faint: the mask keeps only what is 0.8 covered
  std::vector<cv::Point> pts;
  cv::findNonZero(mask, pts);
  int last = 0;
  for (const auto& p : pts) last = std::max(last, p.x);
  EXPECT_GT(end_x - (last + 0.5), 0.7);  // the mask's own end is short
  const auto tip = refine_tail_tip(mask, e, cv::Point2d(1, 0), cv::Point2d(-1, -1));
  EXPECT_NEAR(tip.x, end_x, 0.4);
  EXPECT_GT(tip.y, 23 - 0.5);
  EXPECT_LT(tip.y, 27.4 - 0.5);
}

// A tapered lobe drawn at 1/16 px and blurred (sigma 1 px): 7 px wide at its base, its apex
// at (52.3, 25.2). The half-contrast mask ends 3.8 px short; past it the lobe is still detected
// (darker than the threshold), and the tip read there is 1.2 px short: an apex narrower than
// the blur stays below half of any level the lobe reaches (docs/studies/realistic_footage.md).
TEST(Midline, TheTailTipOfABlurredTaperedLobe) {
  const int scale = 16, W = 70, H = 60;
  const cv::Point2d apex(52.3, 25.2);
  cv::Mat big = cv::Mat::zeros(H * scale, W * scale, CV_8U);
  std::vector<cv::Point> q;
  for (const cv::Point2d& v : {cv::Point2d(5, 22), cv::Point2d(35, 22), apex, cv::Point2d(35, 29), cv::Point2d(35, 38), cv::Point2d(5, 38)})
    q.emplace_back(static_cast<int>(std::lround((v.x + 0.5) * scale)), static_cast<int>(std::lround((v.y + 0.5) * scale)));
  cv::fillPoly(big, std::vector<std::vector<cv::Point>>{q}, cv::Scalar(255));
  cv::Mat cover;
  cv::resize(big, cover, cv::Size(W, H), 0, 0, cv::INTER_AREA);
  cover.convertTo(cover, CV_32F, 1.0 / 255);
  cv::GaussianBlur(cover, cover, cv::Size(0, 0), 1.0);
  TipEvidence e;
  e.darkening = 40 * cover;
  e.threshold = 6;
  const cv::Mat mask = e.darkening > 20;
  const auto tip = refine_tail_tip(mask, e, cv::Point2d(1, 0), cv::Point2d(-1, -1));
  std::vector<cv::Point> pts;
  cv::findNonZero(mask, pts);
  int last = 0;
  for (const auto& p : pts) last = std::max(last, p.x);
  EXPECT_GT(apex.x - (last + 0.5), 3.0);
  EXPECT_LT(tip.x, apex.x + 0.2);
  EXPECT_GT(tip.x, apex.x - 1.5);
  EXPECT_NEAR(tip.y, apex.y, 0.5);
}

#ifdef FIN_TRACK_EXE
TEST(FinTrackMidline, AnAviClipGivesTheTailBeatInPxAndMm) {
  const Swimmer s;
  const auto dir = std::filesystem::temp_directory_path() / ("fin_track_midline_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  {
    cv::VideoWriter w((dir / "swim.avi").string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), s.fps, cv::Size(240, 160), false);
    ASSERT_TRUE(w.isOpened());
    for (int k = 0; k < 64; ++k) {
      cv::Mat img(160, 240, CV_8U, cv::Scalar(215));
      img.setTo(90, s.mask(k / s.fps));
      w.write(img);
    }
  }
  const std::string cmd = std::string(FIN_TRACK_EXE) + " --log-level warn midline --frames " + (dir / "swim.avi").string() +
                          " --out " + (dir / "m.h5").string() + " --csv " + (dir / "m.csv").string() + " --overlay " +
                          (dir / "o.avi").string() + " --mm-per-px 0.1 2> " + (dir / "err").string();
  const int rc = std::system(cmd.c_str());
  std::ifstream err_in(dir / "err");
  const std::string err{std::istreambuf_iterator<char>(err_in), {}};
  ASSERT_EQ(WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, 0) << err;
  const auto f = finverse::h5::File::open_read(dir / "m.h5");
  EXPECT_NEAR(*f.attr_double(".", "fps"), s.fps, 1e-9);  // from the container
  EXPECT_NEAR(*f.attr_double(".", "tail_beat_frequency_hz"), s.f, 0.01 * s.f);
  const double a_px = *f.attr_double(".", "tail_beat_amplitude_px");
  EXPECT_NEAR(a_px, s.a_tail, 0.05 * s.a_tail);
  EXPECT_NEAR(*f.attr_double(".", "tail_beat_amplitude_mm"), 0.1 * a_px, 1e-12);
  EXPECT_EQ(f.read_f64("mm/tip").shape, (std::vector<std::size_t>{64, 2}));
  std::ifstream csv(dir / "m.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(
      header,
      "frame,time_s,valid,tip_x_px,tip_y_px,tip_lateral_px,tip_x_mm,tip_y_mm,tip_lateral_mm,segmentation_doubt,reason");
  cv::VideoCapture overlay((dir / "o.avi").string());
  ASSERT_TRUE(overlay.isOpened());
  EXPECT_EQ(static_cast<int>(overlay.get(cv::CAP_PROP_FRAME_COUNT)), 64);
  std::filesystem::remove_all(dir);
}
#endif
