// Area-coverage silhouettes and their IoU (issue 5 accuracy scoring).
#include "vision/silhouette_coverage.hpp"

#include <opencv2/imgproc.hpp>

#include "core/error.hpp"
#include "vision/silhouette_residual.hpp"

namespace finverse::vision {

Camera supersampled(const Camera& c, int S) {
  // Fine pixel u' = S (u + 1/2) - 1/2: the affine map of the image plane, applied to K.
  Camera f = c;
  f.width = c.width * S;
  f.height = c.height * S;
  f.K(0, 0) = S * c.K(0, 0);
  f.K(0, 1) = S * c.K(0, 1);
  f.K(1, 1) = S * c.K(1, 1);
  f.K(0, 2) = S * (c.K(0, 2) + 0.5) - 0.5;
  f.K(1, 2) = S * (c.K(1, 2) + 0.5) - 0.5;
  return f;
}

cv::Mat silhouette_coverage(const Camera& c, const NdArray<double>& X, const NdArray<std::int32_t>& triangles, int S) {
  if (S < 1 || S > 16) throw Error("silhouette coverage: supersampling must be 1..16, got " + std::to_string(S));
  cv::Mat fine;
  project_model(supersampled(c, S), X, triangles).mask.convertTo(fine, CV_32F, 1.0 / 255);
  if (S == 1) return fine;
  cv::Mat out;
  cv::resize(fine, out, cv::Size(c.width, c.height), 0, 0, cv::INTER_AREA);  // exact S x S box average
  return out;
}

double coverage_iou(const cv::Mat& a, const cv::Mat& b) {
  if (a.size() != b.size()) throw Error("coverage IoU: maps differ in size");
  auto as_float = [](const cv::Mat& m) {
    cv::Mat f;
    m.convertTo(f, CV_32F, m.depth() == CV_8U ? 1.0 / 255 : 1.0);
    return f;
  };
  const cv::Mat fa = as_float(a), fb = as_float(b);
  cv::Mat lo, hi;
  cv::min(fa, fb, lo);
  cv::max(fa, fb, hi);
  const double uni = cv::sum(hi)[0];
  return uni > 0 ? cv::sum(lo)[0] / uni : 1.0;
}

}  // namespace finverse::vision
