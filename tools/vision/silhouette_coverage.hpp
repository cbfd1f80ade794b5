// Anti-aliased silhouettes for scoring (issue 5 accuracy: "silhouette IoU >= 0.97 in every
// view, scored against truth.h5"). A binary silhouette sampled at pixel centres turns a sub-pixel
// shift of an edge into whole pixels gained or lost, and the edge-on views of the thin fin are
// only a few pixels wide, so two surfaces a tenth of a pixel apart can differ by several per cent
// in a binary IoU. Here every pixel instead holds the fraction of its area that the projected
// surface covers (estimated on an S x S grid of sub-pixel samples, the same pixel-centre
// rasteriser as the fit's project_model at S times the resolution, then box-averaged, as the
// renderer anti-aliases), and the IoU of two coverage maps is the area of the overlap over the
// area of the union: sum(min(a, b)) / sum(max(a, b)) (the Ruzicka similarity, which is the
// ordinary IoU for binary masks).
#pragma once

#include <opencv2/core.hpp>

#include "core/nd_array.hpp"
#include "vision/camera.hpp"

namespace finverse::vision {

// The camera seen through an S-times finer pixel grid: pixel centres of the fine grid sit at the
// centres of the S x S sub-pixels of the original pixels (OpenCV convention, centres at integers).
Camera supersampled(const Camera& camera, int S);

// Coverage in [0, 1] (CV_32F, the camera's image size) of the surface X [nv,3] with `triangles`.
// Throws finverse::Error if S is not in 1..16.
cv::Mat silhouette_coverage(const Camera& camera, const NdArray<double>& X, const NdArray<std::int32_t>& triangles, int S = 4);

// sum(min(a, b)) / sum(max(a, b)) of two maps of the same size with values in [0, 1] (CV_32F or
// CV_8U, 8-bit values scaled by 1/255); 1 when both are empty.
double coverage_iou(const cv::Mat& a, const cv::Mat& b);

}  // namespace finverse::vision
