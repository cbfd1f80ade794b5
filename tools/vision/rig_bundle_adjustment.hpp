// Bundle adjustment of a calibrated camera rig (issue 35 item 2): every camera's intrinsics and
// pose and every board pose refined at once over all the board corners every camera found, by
// Levenberg-Marquardt on the reprojection errors (Huber-weighted). The chain of pairwise
// stereoCalibrate links (calibration.hpp) starts it; the links use only the frames of one pair
// each, the adjustment all of them, so each camera's pose is fixed by every frame it shares.
// Gauge: the root camera's pose (the identity; the rig is in its frame) is held fixed.
#pragma once

#include <cstddef>
#include <vector>

#include <opencv2/core.hpp>

#include "vision/camera.hpp"

namespace finverse::vision {

struct RigObservation {
  std::size_t camera = 0, frame = 0;
  std::vector<cv::Point3f> object;          // the board corners found (board frame, m)
  const std::vector<cv::Point2f>* image = nullptr;  // where (px)
};

struct RigState {
  std::vector<Camera> cameras;             // K, dist; rvec/tvec: root camera -> camera
  std::vector<cv::Vec3d> board_r, board_t;  // per frame: board -> root camera (unused where not seen)
};

struct BundleOptions {
  std::size_t root = 0;
  bool intrinsics = true;  // refine them too (else each camera's own calibrateCamera values stay)
  bool fix_k3 = true, fit_tangential = false;
  int iterations = 30;
  double huber_px = 1.0;
  double max_start_rms_px = 5.0;  // a board this far off the starting rig is left out (warned)
};

// Refines `state` in place; returns each camera's RMS reprojection error (px) after.
std::vector<double> bundle_adjust_rig(RigState& state, const std::vector<RigObservation>& observations,
                                      const BundleOptions& options);

}  // namespace finverse::vision
