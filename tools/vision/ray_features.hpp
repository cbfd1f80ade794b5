// Fin-ray features (seed paper section 2.1 step 1 and Fig. 7: the bony rays are the darkest,
// sharpest lines in the backlit images, and they are what the skeleton's chains stand for).
// Rays are found as thin dark structures: the morphological black-hat (closing minus image)
// with a disc a little wider than the widest ray responds to dark lines and not to the broad,
// lighter membrane or the background; a threshold well above the membrane's pigment spots keeps
// the rays. The distance to the nearest ray pixel then pulls the skeleton's projected ray axes
// onto them, so the interior rays, which the silhouettes barely see, are located too.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "vision/normal_equations.hpp"
#include "vision/silhouette_residual.hpp"
#include "vision/view_data.hpp"

namespace finverse::vision {

struct RayFeatureOptions {
  int disc_px = 11;               // black-hat structuring disc (wider than the widest ray)
  double min_contrast = 50;       // 8-bit levels darker than the closing
  double max_distance_px = 6;     // farther model ray points are taken as not seen in this view
  double huber_px = 1.5;
  double weight = 1.0;
};

// Ray pixels (CV_8U, 255) of an 8-bit frame, restricted to the (dilated) fin mask.
cv::Mat detect_rays(const cv::Mat& frame, const cv::Mat& fin_mask, const RayFeatureOptions& options);

// Adds one residual per model ray point (the template vertices on the rays): the distance from
// its projection to the nearest detected ray pixel, truncated at max_distance_px.
double add_ray_residuals(const ViewData& view, const ModelView& model, const std::vector<int>& ray_vertices, const SkinJacobian* J,
                         const RayFeatureOptions& options, NormalEquations& ne);

}  // namespace finverse::vision
