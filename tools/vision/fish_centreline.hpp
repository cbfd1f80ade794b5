// The fish's centreline in one silhouette seen from above, fins left out (issue 47; method and
// measurements: docs/studies/midline_deep_body.md). The body core is the silhouette opened by a
// disc of kCoreFraction of its largest inscribed radius: fins, thinner than the trunk, go; a
// blunt head stays. On slices across the record's axis the middle of the silhouette's run where
// it agrees with the core's. Where it overhangs the core on one side a fin hides that flank, and
// the opening's fillet under the fin keeps the core's edge from serving either, so the middle is
// the clean edge moved by the trunk's half-width fitted through the clean slices. Overhung on
// both sides: the core's middle when the core is whole there, else the silhouette's.
#pragma once

#include <cstddef>
#include <opencv2/core.hpp>
#include <vector>

namespace finverse::vision {

inline constexpr double kCoreFraction = 0.75;
inline constexpr int kSlicesPerStation = 5;
inline constexpr double kEdgePx = 1.5;           // an overhang beyond the core that counts (px)
inline constexpr std::size_t kWidthWindow = 60;  // slices either side that give the half-width

struct BodyCore {
  cv::Mat mask;           // CV_8U, 255 on the core: the largest connected part of the opening
  double half_width = 0;  // the silhouette's largest inscribed radius (px)
};

// The body core of `mask` (CV_8U, non-zero on the fish). Empty when the mask is.
BodyCore body_core(const cv::Mat& mask);

// The centreline's `stations` points (px), head to tail: station b at s = lo + (b + 0.5)(hi - lo) /
// stations along the unit axis `u` from `origin`. NaN where no slice of a station meets the fish.
// Where the silhouette stands in for the core, runs less than half the trunk's half-width apart
// are one (the lobes of a forked caudal fin, spread by its twist, are one fin).
std::vector<cv::Point2d> fish_centreline(const cv::Mat& mask, const BodyCore& core, const cv::Point2d& origin,
                                         const cv::Point2d& u, double lo, double hi, int stations);

}  // namespace finverse::vision
