// The fish's centreline in one silhouette seen from above, with the appendages ignored (issue 47:
// the 2-D mode on deep-bodied fish whose pectoral fins stick out of the silhouette).
//
// The body core is the silhouette opened by a disc whose radius is kCoreFraction of the
// silhouette's largest inscribed radius (the trunk's half-width): a fin, thinner than the trunk,
// is taken off, while the trunk, a blunt head included, keeps its outline wherever its outline is
// rounder than the disc. The opening is exact (Euclidean): the points within r of the points at
// least r deep. Behind the trunk (the peduncle and the caudal fin, narrower than the disc) the
// silhouette itself is used; a fish has no appendage there that sticks out sideways seen from
// above.
//
// The centreline is read on slices across the record's axis, kSlicesPerStation per station at
// one-pixel steps; the station's point is the median of its slices. On each slice, the
// silhouette's run and the core's run inside it. Where they agree (no appendage), the middle of
// the run. Where the silhouette overhangs the core on one side only, a fin is attached there, and
// the flank beneath it is hidden: then the middle is the clean edge moved by the trunk's
// half-width, read off the clean slices around it (a quadratic in s through them). The opening's
// fillet where a fin meets the trunk (a disc that fits in the trunk and the fin's base together)
// is what keeps the core's own edge on that side from serving. Where the silhouette overhangs on
// both sides (the core's rounded ends; fins on both flanks, as symmetric as the body), the middle
// of the silhouette's run.
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
