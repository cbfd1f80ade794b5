// Dark-line detection of the fin rays and their distance residuals (seed paper section 2.1).
#include "vision/ray_features.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace finverse::vision {

cv::Mat detect_rays(const cv::Mat& frame, const cv::Mat& fin_mask, const RayFeatureOptions& o) {
  cv::Mat smooth, hat;
  cv::GaussianBlur(frame, smooth, cv::Size(0, 0), 0.7);
  const auto disc = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(o.disc_px, o.disc_px));
  cv::morphologyEx(smooth, hat, cv::MORPH_BLACKHAT, disc);
  cv::Mat rays = hat > o.min_contrast;
  cv::Mat near_fin;
  cv::dilate(fin_mask, near_fin, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(5, 5)));
  return rays & near_fin;
}

double add_ray_residuals(const ViewData& view, const ModelView& m, const std::vector<int>& ray_vertices, const SkinJacobian* J,
                         const RayFeatureOptions& o, NormalEquations& ne) {
  if (!view.valid || view.ray_distance.empty()) return 0;
  const cv::Mat& f = view.ray_distance;
  double sum2 = 0;
  for (int v : ray_vertices) {
    const auto& u = m.uv[static_cast<std::size_t>(v)];
    if (u.x < 0 || u.y < 0 || u.x > f.cols - 1.001 || u.y > f.rows - 1.001) continue;
    const int i = static_cast<int>(u.x), j = static_cast<int>(u.y);
    const double a = u.x - i, b = u.y - j;
    const double f00 = f.at<float>(j, i), f10 = f.at<float>(j, i + 1), f01 = f.at<float>(j + 1, i), f11 = f.at<float>(j + 1, i + 1);
    const double r = (1 - b) * ((1 - a) * f00 + a * f10) + b * ((1 - a) * f01 + a * f11);
    const double w = o.weight * (r <= o.huber_px ? 1.0 : o.huber_px / r);
    if (r >= o.max_distance_px) {  // truncated: a constant cost, no pull
      ne.cost_only(o.max_distance_px, o.weight * o.huber_px / o.max_distance_px);
      sum2 += o.max_distance_px * o.max_distance_px;
      continue;
    }
    sum2 += r * r;
    if (!J) {
      ne.cost_only(r, w);
      continue;
    }
    const double gx = (1 - b) * (f10 - f00) + b * (f11 - f01);
    const double gy = (1 - a) * (f01 - f00) + a * (f11 - f10);
    const cv::Matx23d& P = m.duv_dX[static_cast<std::size_t>(v)];
    const cv::Vec3d gP(gx * P(0, 0) + gy * P(1, 0), gx * P(0, 1) + gy * P(1, 1), gx * P(0, 2) + gy * P(1, 2));
    const auto& cols = J->cols[static_cast<std::size_t>(v)];
    const auto& vals = J->vals[static_cast<std::size_t>(v)];
    for (std::size_t c = 0; c < cols.size(); ++c) ne.add(cols[c], gP.dot(vals[c]));
    ne.commit(r, w);
  }
  return ray_vertices.empty() ? 0.0 : std::sqrt(sum2 / ray_vertices.size());
}

}  // namespace finverse::vision
