// Symmetric silhouette chamfer residuals with closest-point correspondences (seed paper
// section 2.1, step 1).
#include "vision/silhouette_residual.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "core/error.hpp"

namespace finverse::vision {
namespace {

double bilinear(const cv::Mat& f, double x, double y) {
  x = std::clamp(x, 0.0, f.cols - 1.001);
  y = std::clamp(y, 0.0, f.rows - 1.001);
  const int i = static_cast<int>(x), j = static_cast<int>(y);
  const double a = x - i, b = y - j;
  const double f00 = f.at<float>(j, i), f10 = f.at<float>(j, i + 1), f01 = f.at<float>(j + 1, i), f11 = f.at<float>(j + 1, i + 1);
  return (1 - b) * ((1 - a) * f00 + a * f10) + b * ((1 - a) * f01 + a * f11);
}

// Barycentric coordinates of pixel centre (x, y) in projected triangle t.
std::array<double, 3> barycentric(const ModelView& m, const NdArray<std::int32_t>& tri, int t, double x, double y) {
  const auto& a = m.uv[tri(t, 0)];
  const auto& b = m.uv[tri(t, 1)];
  const auto& c = m.uv[tri(t, 2)];
  const double det = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
  if (std::abs(det) < 1e-12) return {1.0 / 3, 1.0 / 3, 1.0 / 3};
  double l1 = ((x - a.x) * (c.y - a.y) - (c.x - a.x) * (y - a.y)) / det;
  double l2 = ((b.x - a.x) * (y - a.y) - (x - a.x) * (b.y - a.y)) / det;
  // Rasterisation can cover a pixel whose centre lies a hair outside: clamp into the triangle.
  l1 = std::clamp(l1, 0.0, 1.0);
  l2 = std::clamp(l2, 0.0, 1.0 - l1);
  return {1 - l1 - l2, l1, l2};
}

// Buckets of contour pixels for nearest-point queries.
class ContourGrid {
 public:
  ContourGrid(const std::vector<cv::Point>& pts, cv::Size size) : pts_(pts) {
    nx_ = size.width / kCell + 1;
    ny_ = size.height / kCell + 1;
    start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
    for (const auto& p : pts) ++start_[cell(p) + 1];
    for (std::size_t i = 1; i < start_.size(); ++i) start_[i] += start_[i - 1];
    order_.resize(pts.size());
    auto fill = start_;
    for (std::size_t i = 0; i < pts.size(); ++i) order_[fill[cell(pts[i])]++] = static_cast<int>(i);
  }
  cv::Point nearest(cv::Point q) const {
    if (pts_.empty()) return {-1, -1};
    const int cx = q.x / kCell, cy = q.y / kCell;
    long best = std::numeric_limits<long>::max();
    cv::Point out(-1, -1);
    for (int ring = 0; ring < std::max(nx_, ny_); ++ring) {
      // Every point in ring r is at least (r - 1) cells away: stop once that exceeds the best.
      const long reach = static_cast<long>(std::max(0, ring - 1)) * kCell;
      if (out.x >= 0 && reach * reach > best) break;
      for (int y = cy - ring; y <= cy + ring; ++y)
        for (int x = cx - ring; x <= cx + ring; ++x) {
          if (std::max(std::abs(x - cx), std::abs(y - cy)) != ring || x < 0 || y < 0 || x >= nx_ || y >= ny_) continue;
          const std::size_t c = static_cast<std::size_t>(y) * nx_ + x;
          for (std::size_t k = start_[c]; k < start_[c + 1]; ++k) {
            const auto& p = pts_[static_cast<std::size_t>(order_[k])];
            const long d = static_cast<long>(p.x - q.x) * (p.x - q.x) + static_cast<long>(p.y - q.y) * (p.y - q.y);
            if (d < best) best = d, out = p;
          }
        }
    }
    return out;
  }

 private:
  static constexpr int kCell = 8;
  std::size_t cell(cv::Point p) const { return static_cast<std::size_t>(p.y / kCell) * nx_ + p.x / kCell; }
  const std::vector<cv::Point>& pts_;
  int nx_, ny_;
  std::vector<std::size_t> start_;
  std::vector<int> order_;
};

bool in_body(const ViewData& view, cv::Point2d u) {
  if (view.body.empty()) return false;
  const int x = static_cast<int>(std::lround(u.x)), y = static_cast<int>(std::lround(u.y));
  return x >= 0 && y >= 0 && x < view.body.cols && y < view.body.rows && view.body.at<std::uint8_t>(y, x);
}

double huber_weight(double r, double k) { return std::abs(r) <= k ? 1.0 : k / std::abs(r); }

// Adds g . d(uv)/dp of the surface point (barycentric combination of a triangle's vertices).
void add_point_row(const ModelView& m, const NdArray<std::int32_t>& tri, int t, const std::array<double, 3>& bc,
                   const SkinJacobian& J, double gx, double gy, NormalEquations& ne) {
  for (int k = 0; k < 3; ++k) {
    const auto v = static_cast<std::size_t>(tri(t, k));
    const cv::Matx23d& P = m.duv_dX[v];
    // Row vector g^T P (1 x 3), weighted by the barycentric coordinate.
    const cv::Vec3d gP(bc[k] * (gx * P(0, 0) + gy * P(1, 0)), bc[k] * (gx * P(0, 1) + gy * P(1, 1)),
                       bc[k] * (gx * P(0, 2) + gy * P(1, 2)));
    const auto& cols = J.cols[v];
    const auto& vals = J.vals[v];
    for (std::size_t c = 0; c < cols.size(); ++c) ne.add(cols[c], gP.dot(vals[c]));
  }
}

}  // namespace

double sample_distance(const cv::Mat& f, double x, double y, double* gx, double* gy) {
  *gx = bilinear(f, x + 0.5, y) - bilinear(f, x - 0.5, y);
  *gy = bilinear(f, x, y + 0.5) - bilinear(f, x, y - 0.5);
  return bilinear(f, x, y);
}

ModelView project_model(const Camera& cam, const NdArray<double>& X, const NdArray<std::int32_t>& tri) {
  const std::size_t nv = X.dim(0);
  const cv::Matx33d R = cam.rotation();
  // Camera::project with the rotation computed once (it is called seven times per vertex).
  auto project = [&](const cv::Vec3d& w) {
    const cv::Vec3d Xc = R * w + cam.tvec;
    const double x = Xc[0] / Xc[2], y = Xc[1] / Xc[2];
    const double k1 = cam.dist[0], k2 = cam.dist[1], p1 = cam.dist[2], p2 = cam.dist[3], k3 = cam.dist[4];
    const double r2 = x * x + y * y;
    const double radial = 1 + r2 * (k1 + r2 * (k2 + r2 * k3));
    const double xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x);
    const double yd = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y;
    return cv::Point2d(cam.K(0, 0) * xd + cam.K(0, 1) * yd + cam.K(0, 2), cam.K(1, 1) * yd + cam.K(1, 2));
  };
  ModelView m;
  m.uv.resize(nv);
  m.duv_dX.resize(nv);
  const double h = 1e-7;  // metres; a fraction of a micron
  for (std::size_t v = 0; v < nv; ++v) {
    const cv::Vec3d p(X(v, 0), X(v, 1), X(v, 2));
    m.uv[v] = project(p);
    for (int d = 0; d < 3; ++d) {
      cv::Vec3d q = p;
      q[d] += h;
      const auto up = project(q);
      q[d] -= 2 * h;
      const auto um = project(q);
      m.duv_dX[v](0, d) = (up.x - um.x) / (2 * h);
      m.duv_dX[v](1, d) = (up.y - um.y) / (2 * h);
    }
  }
  // Pixel-centre sampling (a pixel is the fin's when its centre is), the same convention as a
  // coverage threshold of one half in the data, so neither silhouette is biased outwards.
  m.triangle.create(cam.height, cam.width, CV_32S);
  std::fill_n(m.triangle.ptr<int>(), m.triangle.total(), -1);  // (a Scalar fill is several times slower)
  for (std::size_t t = 0; t < tri.dim(0); ++t) {
    const auto& a = m.uv[tri(t, 0)];
    const auto& b = m.uv[tri(t, 1)];
    const auto& c = m.uv[tri(t, 2)];
    const double area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
    if (area == 0) continue;
    const double sgn = area > 0 ? 1.0 : -1.0;
    const int x0 = std::max(0, static_cast<int>(std::ceil(std::min({a.x, b.x, c.x}))));
    const int x1 = std::min(cam.width - 1, static_cast<int>(std::floor(std::max({a.x, b.x, c.x}))));
    const int y0 = std::max(0, static_cast<int>(std::ceil(std::min({a.y, b.y, c.y}))));
    const int y1 = std::min(cam.height - 1, static_cast<int>(std::floor(std::max({a.y, b.y, c.y}))));
    for (int y = y0; y <= y1; ++y) {
      int* row = m.triangle.ptr<int>(y);
      for (int x = x0; x <= x1; ++x) {
        const double e0 = sgn * ((c.x - b.x) * (y - b.y) - (c.y - b.y) * (x - b.x));
        const double e1 = sgn * ((a.x - c.x) * (y - c.y) - (a.y - c.y) * (x - c.x));
        const double e2 = sgn * ((b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x));
        if (e0 >= 0 && e1 >= 0 && e2 >= 0) row[x] = static_cast<int>(t);
      }
    }
  }
  m.mask = m.triangle >= 0;
  return m;
}

SilhouetteStats add_silhouette_residuals(const ViewData& view, const ModelView& m, const NdArray<std::int32_t>& tri,
                                         const SkinJacobian* J, const SilhouetteOptions& o, NormalEquations& ne) {
  SilhouetteStats st;
  if (!view.valid) return st;
  double sum2 = 0;
  const int stride = std::max(1, o.contour_stride);
  // model -> data: contour pixels of the model silhouette onto the data's signed distance. An
  // inner contour pixel centre sits half a pixel inside its silhouette, hence the -0.5 target.
  const auto model_contour = inner_contour(m.mask);
  for (std::size_t i = 0; i < model_contour.size(); i += stride) {
    const auto q = model_contour[i];
    const int t = m.triangle.at<int>(q);
    const auto bc = barycentric(m, tri, t, q.x, q.y);
    cv::Point2d u(0, 0);
    for (int k = 0; k < 3; ++k) u += bc[k] * m.uv[tri(t, k)];
    if (in_body(view, u)) continue;  // behind or on the opaque body: the image cannot tell
    double gx, gy;
    const double r = sample_distance(view.sdf, u.x, u.y, &gx, &gy) + 0.5;
    const double w = o.weight * huber_weight(r, o.huber_px);
    sum2 += r * r;
    ++st.residuals;
    if (!J) {
      ne.cost_only(r, w);
      continue;
    }
    add_point_row(m, tri, t, bc, *J, gx, gy, ne);
    ne.commit(r, w);
  }
  // data -> model: uncovered data contour pixels pull the nearest model surface point. The
  // nearest model pixel to an outside point lies on the model's contour; a bucket grid over the
  // contour finds it.
  const ContourGrid grid(model_contour, m.mask.size());
  for (std::size_t i = 0; i < view.contour.size(); i += stride) {
    const auto q = view.contour[i];
    if (!view.body.empty() && view.body.at<std::uint8_t>(q)) continue;  // the body's outline, not the fin's
    if (m.mask.at<std::uint8_t>(q)) {  // covered: this direction is satisfied
      ++st.residuals;
      continue;
    }
    const auto p = grid.nearest(q);
    if (p.x < 0) continue;
    const int t = m.triangle.at<int>(p);
    const auto bc = barycentric(m, tri, t, p.x, p.y);
    cv::Point2d u(0, 0);
    for (int k = 0; k < 3; ++k) u += bc[k] * m.uv[tri(t, k)];
    cv::Point2d n(q.x - u.x, q.y - u.y);
    const double len = std::hypot(n.x, n.y);
    if (len < 1e-9) continue;
    n *= 1.0 / len;
    // Residual: how far the model's edge (half a pixel past its contour pixel) falls short of q.
    const double r = len - 0.5;
    const double w = o.weight * huber_weight(r, o.huber_px);
    sum2 += r * r;
    ++st.residuals;
    if (!J) {
      ne.cost_only(r, w);
      continue;
    }
    add_point_row(m, tri, t, bc, *J, -n.x, -n.y, ne);
    ne.commit(r, w);
  }
  st.rms_px = st.residuals ? std::sqrt(sum2 / st.residuals) : 0.0;
  return st;
}

}  // namespace finverse::vision
