// Ray root and tip keypoints in the skeleton fit (see keypoint_residual.hpp).
#include "vision/keypoint_residual.hpp"

#include <cmath>

#include "core/error.hpp"

namespace finverse::vision {

namespace {

cv::Vec3d vertex(const NdArray<double>& X, int v) {
  const auto i = static_cast<std::size_t>(v);
  return {X(i, 0), X(i, 1), X(i, 2)};
}

// The two rows of a 2-D keypoint: r_c = uv_c - target_c, dr_c/dp = d(uv_c)/dX . dX/dp.
void add_image_rows(const SkinJacobian* J, int v, const cv::Matx<double, 2, 3>& duv, const double* r, double weight,
                    NormalEquations& ne) {
  for (int c = 0; c < 2; ++c) {
    if (!J) {
      ne.cost_only(r[c], weight);
      continue;
    }
    const auto& cols = J->cols[static_cast<std::size_t>(v)];
    const auto& vals = J->vals[static_cast<std::size_t>(v)];
    for (std::size_t k = 0; k < cols.size(); ++k) ne.add(cols[k], duv(c, 0) * vals[k][0] + duv(c, 1) * vals[k][1] + duv(c, 2) * vals[k][2]);
    ne.commit(r[c], weight);
  }
}

}  // namespace

double add_keypoint_residuals(const std::vector<ViewData>& views, const FrameKeypoints& k, const RayEnds& ends,
                              const NdArray<double>& X, const SkinJacobian* J, const KeypointOptions& o, double chord,
                              NormalEquations& ne) {
  if (o.weight <= 0) return 0;
  double sum2 = 0;
  for (const auto& kp : k.image) {
    if (kp.view >= views.size()) throw Error("keypoints: view index out of range");
    const Camera& cam = views[kp.view].camera;
    const int v = ends.vertex(kp.ray, kp.end);
    const cv::Vec3d x = vertex(X, v);
    const cv::Point2d uv = cam.project(x);
    // d(uv)/dX by central differences (a few keypoints: the full model projection is not needed).
    cv::Matx<double, 2, 3> duv;
    const double h = 1e-6 * chord;
    for (int c = 0; c < 3; ++c) {
      cv::Vec3d a = x, b = x;
      a[c] += h, b[c] -= h;
      const cv::Point2d d = (cam.project(a) - cam.project(b)) * (0.5 / h);
      duv(0, c) = d.x, duv(1, c) = d.y;
    }
    const double r[2] = {uv.x - kp.uv.x, uv.y - kp.uv.y};
    const double dist = std::hypot(r[0], r[1]);
    sum2 += dist * dist;
    add_image_rows(J, v, duv, r, o.weight * (dist <= o.huber_px ? 1.0 : o.huber_px / dist), ne);
  }
  const double sigma = o.sigma_3d_chords * chord;
  for (const auto& kp : k.world) {
    const int v = ends.vertex(kp.ray, kp.end);
    const cv::Vec3d d = (vertex(X, v) - kp.X) / sigma;
    const double dist = cv::norm(d);
    const double w = o.weight * (dist <= o.huber_px ? 1.0 : o.huber_px / dist);
    for (int c = 0; c < 3; ++c) {
      if (!J) {
        ne.cost_only(d[c], w);
        continue;
      }
      const auto& cols = J->cols[static_cast<std::size_t>(v)];
      const auto& vals = J->vals[static_cast<std::size_t>(v)];
      for (std::size_t q = 0; q < cols.size(); ++q) ne.add(cols[q], vals[q][c] / sigma);
      ne.commit(d[c], w);
    }
  }
  return k.image.empty() ? 0.0 : std::sqrt(sum2 / static_cast<double>(k.image.size()));
}

}  // namespace finverse::vision
