// Per-view preprocessing of a frame: silhouette, distance fields, ray features.
#include "vision/view_data.hpp"

#include <opencv2/imgproc.hpp>

#include "core/error.hpp"
#include "vision/ray_features.hpp"

namespace finverse::vision {

ViewData prepare_view(const Camera& camera, const cv::Mat& frame, const SegmentationOptions& so, const RayFeatureOptions& ro,
                      const SegmentationContext& context) {
  ViewData v;
  v.camera = camera;
  if (frame.empty()) return v;
  if (frame.cols != camera.width || frame.rows != camera.height)
    throw Error("view '" + camera.name + "': frame is " + std::to_string(frame.cols) + "x" + std::to_string(frame.rows) +
                " px but the calibration says " + std::to_string(camera.width) + "x" + std::to_string(camera.height));
  const auto seg = segment_fin(frame, so, context);
  v.touches_border = seg.touches_border, v.lost = seg.lost, v.fin_cut = seg.fin_cut;
  v.mask = seg.mask;
  v.coverage = seg.coverage;
  v.body = seg.body;
  v.valid = cv::countNonZero(v.mask) > 0;
  if (!v.valid) return v;
  v.sdf = signed_distance(v.mask);
  v.contour = inner_contour(v.mask);
  if (ro.weight > 0) {
    const cv::Mat rays = detect_rays(frame, v.mask, ro);
    if (cv::countNonZero(rays) > 0) cv::distanceTransform(rays == 0, v.ray_distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  }
  return v;
}

}  // namespace finverse::vision
