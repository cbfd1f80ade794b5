// The 2-D single-view mode (issue 35, item 4; the common case: one camera looking down on the
// fish): per frame the fish's midline, its tail tip and the tip's lateral excursion; over the
// record the tail-beat frequency, amplitude and body wavelength (the quantities trackter and
// similar tools report). The midline is sampled along the fish's mean axis over the record (a
// swimming fish's heading changes slowly against its undulation): at each of `stations` equal
// steps from head to tail, the middle of the body's run across the axis, its fins left out
// (fish_centreline.hpp, issue 47). The tail tip is the silhouette's end on the axis, refined in
// the image where given (refine_tail_tip). A frame whose midline, snout to tail tip, is shorter
// than the record's median by more than kLostFinFraction has lost the fin (its end jumped back to
// the peduncle): not measured, with its reason. Lateral: across the mean axis, from the centroid
// averaged over one whole beat (frequency found on the tip's excursion from the frame's own
// centroid).
//   frequency: the spectral peak of the tip's lateral excursion (parabolic refinement of the
//     DFT magnitude, mean removed, Hann window);
//   amplitude: half the mean peak-to-peak excursion per beat;
//   wavelength: 2 pi over the slope of the excursion's phase (at the tail-beat frequency) along
//     the posterior half of the midline.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace finverse::vision {

// A bending fish shortens on its mean axis by a few per cent (1 - cos 20 deg = 6 %); a lost caudal
// fin takes a fifth of it (fin-synth's fish: the fin's chord over 5 chords).
inline constexpr double kLostFinFraction = 0.1;

struct MidlineFrame {
  bool valid = false;
  bool lost_fin = false;            // the silhouette's end jumped back (not valid)
  std::string reason;               // why the frame is not valid (empty when it is)
  std::vector<cv::Point2d> points;  // head to tail (px); NaN where a station has no pixel
  cv::Point2d tip;                  // tail tip (px)
  cv::Point2d centroid;             // of the silhouette (px): the lateral excursions' reference
};

struct TailBeat {
  double frequency_hz = 0, amplitude_px = 0, wavelength_px = 0;
  std::vector<double> tip_lateral_px;  // per frame, across the mean axis; NaN: no fish
  cv::Point2d axis{1, 0};              // the mean axis, head to tail (unit)
  int beats = 0;                       // whole beats the amplitude averages over
};

// What the tail tip's sub-pixel refinement reads of one frame: the darkening (the segmentation's
// background minus the frame, 8-bit levels, CV_32F) over a window around the fish whose top-left
// corner is `origin` in the frame, and the darkening that counts as fin (the segmentation's).
struct TipEvidence {
  cv::Mat darkening;
  cv::Point origin{0, 0};
  double threshold = 0;
  double blur_sigma = 0;  // the segmentation's pre-smoothing (px) under which `threshold` holds
};

// The tail tip to sub-pixel precision: the point of the fin's outline farthest along `axis`, as
// the truth and a user define it. The binary mask ends short of faint, blurred lobe tips, so each
// line along the axis (every quarter pixel across the mask's last kTipWindowPx) follows the fin in
// the grey image while it is still detected and puts the edge where the darkening falls to half the
// lobe's level, at most kTipReachPx past the mask; the farthest edge wins, else `fallback`. Rule,
// limits and biases: docs/studies/realistic_footage.md.
inline constexpr double kTipWindowPx = 6;
inline constexpr double kTipReachPx = 3;
inline constexpr double kTipLevelPx = 2;
cv::Point2d refine_tail_tip(const cv::Mat& mask, const TipEvidence& evidence, const cv::Point2d& axis,
                            const cv::Point2d& fallback);

// The midline of each mask, all on the record's mean axis, oriented so that the head is the end
// with more area (the body; the caudal fin is thinner seen from above) in the record's sum. With
// `evidence` (one per mask), the tail tips are refined from the image (refine_tail_tip).
std::vector<MidlineFrame> extract_midlines(const std::vector<cv::Mat>& masks, int stations, cv::Point2d* axis_out = nullptr,
                                           const std::vector<TipEvidence>* evidence = nullptr);

// Tail-beat frequency, amplitude and body wavelength of the record (frames at `fps`).
TailBeat tail_beat(const std::vector<MidlineFrame>& midlines, const cv::Point2d& axis, double fps);

}  // namespace finverse::vision
