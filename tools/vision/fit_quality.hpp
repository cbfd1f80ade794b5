// Whether a 3-D fit can be trusted (issue 35, item 5): per-frame doubts and the run's verdict.
// A fit the views cannot constrain must not look like a result: one view leaves the fin's depth
// free (looking straight down the fin it stays in its rest pose; tilted, it slides towards the
// camera until its enlarged silhouette covers the fish), a template of the wrong size cannot
// match the silhouettes, and a fit that lost the fin covers nothing. fin-track writes the record
// with these flags and exits 1 with the first failing reason (tools/apps/fin-track.cpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace finverse::vision {

// Bits of kinematics.h5's quality/flags, per frame.
enum FrameFlag : std::uint8_t {
  kFewViews = 1,            // fewer than min_views views showed the fin: its depth is free
  kLowIoU = 2,              // a view's silhouette IoU below min_iou
  kRootDrift = 4,           // the root moved more than max_root_drift chords from the first frame's
  kScaleMismatch = 8,       // a view's fitted over segmented area outside [1/max, max]_area_ratio
  kSegmentationDoubt = 16,  // a view's blob touched the border or none was near the last fish
};

struct FitQualityOptions {
  int min_views = 2;             // views per frame that fix the fin in depth
  double min_iou = 0.3;          // silhouette IoU below this: the fit does not cover the fin
  double max_root_drift = 1.0;   // chords; the root heaves, but not this far (0: not checked)
  double max_area_ratio = 2.0;   // the template's silhouette over the segmented one, either way
};

// One frame as the judge sees it; vectors per view, NaN / 0 where the view had no frame.
struct FrameQuality {
  std::vector<double> iou, area_ratio;
  std::vector<char> valid, doubt;
  double root_drift = 0;  // chords from the first frame's root position
  long frame = 0;         // its index in the record (messages)
};

struct FitVerdict {
  std::vector<std::uint8_t> flags;  // per frame
  std::string failure;              // empty: the fit can be trusted; else one line why not
  bool flagged() const;             // some frame has a flag
};

// Judges the record. A run fails (in this order) when more than half the frames have fewer
// than min_views views; when in some view the median over frames of the area ratio is outside
// [1/max, max]; when the median over frames of the worst view's IoU is below min_iou; when the
// root drifted further than max_root_drift chords in any frame.
FitVerdict judge_fit(const std::vector<FrameQuality>& frames, const std::vector<std::string>& views,
                     const FitQualityOptions& options);

}  // namespace finverse::vision
