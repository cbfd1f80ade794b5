// The caudal fin cut from the fish's body in a silhouette (issue 35, item 3). Real footage shows
// the body and the fin as one blob; the fit needs the fin alone. The cut is at the peduncle: along
// the blob's midline (its principal axis; the width profile is the blob's area per unit length,
// which a moderate bend of the body leaves alone) the body is the widest part, the peduncle the
// narrowest point between the body and the tail end, and the caudal fin spreads again behind it.
// The cut is made only where that shape is clear (body >= body_ratio and fin >= fin_ratio times
// the peduncle width); otherwise the blob is kept whole and the result says so. A user who knows
// better gives a rectangle per view that holds the fin (fin_region_mask). With a calibration, the
// body is cut off at the projected root plane instead (root_plane_line).
#pragma once

#include <opencv2/core.hpp>

namespace finverse::vision {

struct FinCutOptions {
  double body_ratio = 1.5;  // the body's widest part over the peduncle width, at least
  double fin_ratio = 1.3;   // the fin's widest part behind the peduncle over its width, at least
  int bins = 64;            // width-profile samples along the midline
};

struct FinCut {
  cv::Mat fin;              // CV_8U, 255 on the fin (the whole blob when not cut)
  bool cut = false;         // a peduncle was found and the body removed
  double peduncle_px = 0;   // width at the cut
  double body_px = 0;       // the body's widest
  double fin_px = 0;        // the fin's widest
  cv::Point2d at;           // the cut's centre on the midline (px)
  cv::Point2d tailward;     // unit vector along the midline towards the tail
};

// With `fin_side` (a calibrated view's root_plane_line), the fin is the end of the blob on the
// line's positive side, not the end with less area (the border may cut the body short).
FinCut separate_caudal_fin(const cv::Mat& mask, const FinCutOptions& options = {}, const cv::Vec3d* fin_side = nullptr);

// The blob inside `region` (x0, y0, x1, y1 in px, inclusive-exclusive).
cv::Mat fin_region_mask(const cv::Mat& mask, const cv::Rect& region);

// The image line of the fin's root plane (world x = -0.02 c, just upstream of the template's root
// at x = 0, the body upstream at x < 0; DESIGN.md 5.5) in a view that sees that plane edge-on enough to draw it as a line (its
// optical axis at least 60 degrees from x): (a, b, c) with a u + b v + c > 0 on the fin's side,
// a^2 + b^2 = 1. None in a view looking along the body (from behind: the body hides behind the
// fin there and cannot be cut off). `camera` is passed as its projection of world points.
struct Camera;
bool root_plane_line(const Camera& camera, double chord, cv::Vec3d& line);

// The mask's pixels whose centres lie on the fin's side of `line`.
cv::Mat fin_side_mask(const cv::Mat& mask, const cv::Vec3d& line);

}  // namespace finverse::vision
