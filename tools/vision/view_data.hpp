// What one calibrated view contributes to a frame's fit (DESIGN.md section 5.5, fin-track): the
// camera and, when its frame is present, the segmented fin silhouette with its signed distance
// field and contour (segmentation.hpp) and the distance field of the detected fin rays
// (ray_features.hpp). Prepared once per frame and view, before the fit iterates.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "vision/camera.hpp"
#include "vision/segmentation.hpp"

namespace finverse::vision {

struct RayFeatureOptions;

struct ViewData {
  Camera camera;
  bool valid = false;
  cv::Mat mask;                     // CV_8U data silhouette
  cv::Mat sdf;                      // its signed distance field (px)
  cv::Mat coverage;                 // CV_32F soft segmentation (Segmentation::coverage)
  std::vector<cv::Point> contour;   // inner contour pixels of the data silhouette
  cv::Mat ray_distance;             // CV_32F distance (px) to the nearest detected ray pixel
  // The segmentation's doubts (segmentation.hpp): the blob touches the border; no blob near the
  // previous frame's fish (then not valid); the body was cut off at the peduncle.
  bool touches_border = false, lost = false, fin_cut = false;
  // CV_8U the opaque body seen behind or beside the fin (Segmentation::body; empty: none): no
  // residual or score reads these pixels.
  cv::Mat body;
};

// An empty `frame` gives an invalid (missing) view. Throws finverse::Error naming the view when
// the frame's size differs from the calibration's.
ViewData prepare_view(const Camera& camera, const cv::Mat& frame, const SegmentationOptions& segmentation,
                      const RayFeatureOptions& rays, const SegmentationContext& context = {});

}  // namespace finverse::vision
