// The sub-pixel coverage term (coverage_residual.hpp) and the soft segmentation behind it:
// the half-plane coverage is the exact area, the model coverage of tilted strips (also one lying
// partly over another) matches a 16 x 16 supersampled rasterisation to a small fraction of a
// pixel, its Jacobian is the derivative of the cost, Gauss-Newton on it places both edges of a
// strip to a few hundredths of a pixel, and the soft segmentation of a noisy strip adds up to its
// width.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "vision/coverage_residual.hpp"
#include "vision/segmentation.hpp"
#include "vision/silhouette_coverage.hpp"
#include "front_camera.hpp"

using namespace finverse;
using namespace finverse::vision;
using finverse::vision::test::front_camera;
using finverse::vision::test::kD;
using finverse::vision::test::kF;

namespace {

// A strip of width w (px) centred on pixel column u0 at row 31.5, tilted by `angle` from the
// image's vertical, 40 px long, as an n x 2 grid of quads (interior edges that are no outline).
struct Strip {
  NdArray<double> X;
  NdArray<std::int32_t> tri;
};
Strip strip(double u0, double w, double angle, double depth = 0) {
  const Camera c = front_camera();
  const int n = 4;
  Strip s{NdArray<double>({static_cast<std::size_t>(3 * (n + 1)), 3}), NdArray<std::int32_t>({static_cast<std::size_t>(4 * n), 3})};
  const double ca = std::cos(angle), sa = std::sin(angle);
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j < 3; ++j) {
      const double along = -20 + 40.0 * i / n, across = (j - 1) * 0.5 * w;
      const double u = u0 + across * ca + along * sa, v = 31.5 + along * ca - across * sa;
      const int k = 3 * i + j;
      s.X(k, 0) = (u - c.K(0, 2)) * kD / kF;
      s.X(k, 1) = depth;
      s.X(k, 2) = -(v - c.K(1, 2)) * kD / kF;
    }
  int t = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 2; ++j) {
      const int a = 3 * i + j, b = a + 1, d = a + 3, e = a + 4;
      s.tri(t, 0) = a, s.tri(t, 1) = b, s.tri(t, 2) = e, ++t;
      s.tri(t, 0) = a, s.tri(t, 1) = e, s.tri(t, 2) = d, ++t;
    }
  return s;
}

Strip merge(const Strip& p, const Strip& q) {
  const std::size_t np = p.X.dim(0), tp = p.tri.dim(0);
  Strip s{NdArray<double>({np + q.X.dim(0), 3}), NdArray<std::int32_t>({tp + q.tri.dim(0), 3})};
  std::copy(p.X.data.begin(), p.X.data.end(), s.X.data.begin());
  std::copy(q.X.data.begin(), q.X.data.end(), s.X.data.begin() + p.X.data.size());
  std::copy(p.tri.data.begin(), p.tri.data.end(), s.tri.data.begin());
  for (std::size_t i = 0; i < q.tri.data.size(); ++i) s.tri.data[p.tri.data.size() + i] = q.tri.data[i] + static_cast<std::int32_t>(np);
  return s;
}

// Sum of |analytic - supersampled| over the image, per pixel of outline length (px): the mean
// misplacement of the outline.
double outline_error(const Strip& s, double outline_length) {
  const Camera c = front_camera();
  const auto m = project_model(c, s.X, s.tri);
  const auto edges = mesh_edges(s.tri);
  const ModelCoverage cover(m, s.tri, edges);
  const cv::Mat a = cover.image(), b = silhouette_coverage(c, s.X, s.tri, 16);
  return cv::norm(a, b, cv::NORM_L1) / outline_length;
}

}  // namespace

TEST(CoverageResidual, HalfPlaneCoverageIsTheExactArea) {
  for (double angle : {0.0, 0.3, std::numbers::pi / 4, 1.2, 2.5}) {
    const double nx = std::cos(angle), ny = std::sin(angle);
    for (double d : {-0.8, -0.55, -0.3, -0.05, 0.0, 0.12, 0.4, 0.62}) {
      // Midpoint rule on a 400 x 400 grid of the pixel.
      const int N = 400;
      int in = 0;
      for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) in += nx * ((i + 0.5) / N - 0.5) + ny * ((j + 0.5) / N - 0.5) <= d;
      double slope, s2;
      const double c = half_plane_coverage(d, nx, ny, &slope);
      EXPECT_NEAR(c, static_cast<double>(in) / (N * N), 4e-3) << "angle " << angle << " d " << d;
      const double h = 1e-6;
      const double fd = (half_plane_coverage(d + h, nx, ny, &s2) - half_plane_coverage(d - h, nx, ny, &s2)) / (2 * h);
      EXPECT_NEAR(slope, fd, 1e-4) << "angle " << angle << " d " << d;
    }
  }
}

TEST(CoverageResidual, ModelCoverageOfTiltedStripsMatchesSupersampling) {
  for (double angle : {0.0, 0.07, 0.4, 0.785}) {
    for (double w : {4.3, 6.75}) {
      const double e = outline_error(strip(30.2, w, angle), 2 * 40 + 2 * w);
      EXPECT_LT(e, 0.02) << "angle " << angle << " width " << w;
    }
  }
  // Narrower than a pixel: a sliver 0.8 px wide, and a gap of 0.7 px between two prongs (the
  // fork seen edge-on), where both facing edges cut the same pixels.
  EXPECT_LT(outline_error(strip(30.2, 0.8, 0.3), 2 * 40), 0.03);
  EXPECT_LT(outline_error(merge(strip(28.0, 2.0, 0.1), strip(30.7, 2.0, 0.1)), 4 * 40), 0.03);
  // A strip lying across another one (nearer the camera): the hidden parts of either outline
  // must not thin the union.
  const auto cross_strips = merge(strip(30.2, 5.1, 0.1), strip(31.0, 4.6, 1.3, -0.001));
  EXPECT_LT(outline_error(cross_strips, 4 * 40), 0.03);
}

TEST(CoverageResidual, JacobianIsTheDerivativeOfTheCost) {
  const Camera c = front_camera();
  // Data: the coverage of a strip 0.3 px to the right and 0.4 px wider than the model's.
  ViewData view;
  view.camera = c;
  view.valid = true;
  const auto data = strip(30.5, 5.2, 0.2);
  view.coverage = silhouette_coverage(c, data.X, data.tri, 16);
  view.mask = view.coverage > 0.5f;
  view.sdf = signed_distance(view.mask);
  const auto s = strip(30.2, 4.8, 0.2);
  const auto edges = mesh_edges(s.tri);
  // Parameters: x of the strip's left, middle and right columns of vertices.
  SkinJacobian J;
  J.cols.resize(s.X.dim(0));
  J.vals.resize(s.X.dim(0));
  for (std::size_t v = 0; v < s.X.dim(0); ++v) J.cols[v] = {static_cast<int>(v % 3)}, J.vals[v] = {cv::Vec3d(1, 0, 0)};
  CoverageOptions o;
  o.huber = 10;
  auto cost = [&](const std::array<double, 3>& dx) {
    auto X = s.X;
    for (std::size_t v = 0; v < X.dim(0); ++v) X(v, 0) += dx[v % 3];
    NormalEquations ne(3);
    add_coverage_residuals(view, project_model(c, X, s.tri), s.tri, edges, nullptr, o, ne);
    return ne.cost();
  };
  NormalEquations ne(3);
  add_coverage_residuals(view, project_model(c, s.X, s.tri), s.tri, edges, &J, o, ne);
  EXPECT_NEAR(ne.cost(), cost({0, 0, 0}), 1e-9);
  const double h = 1e-3 * kD / kF;  // a thousandth of a pixel
  for (int k = 0; k < 3; k += 2) {
    std::array<double, 3> p{0, 0, 0}, m{0, 0, 0};
    p[k] = h, m[k] = -h;
    const double fd = (cost(p) - cost(m)) / (2 * h);
    EXPECT_NEAR(2 * ne.g()[k], fd, 0.02 * std::abs(fd) + 1e-6) << "column " << k;
    EXPECT_GT(std::abs(fd), 1.0);  // the edges do feel the data
  }
}

TEST(CoverageResidual, GaussNewtonPlacesBothEdgesOfAStrip) {
  const Camera c = front_camera();
  ViewData view;
  view.camera = c;
  view.valid = true;
  const double true_left = 30.37 - 2.61, true_right = 30.37 + 2.61;
  const auto data = strip(30.37, 5.22, 0.15);
  view.coverage = silhouette_coverage(c, data.X, data.tri, 16);
  view.mask = view.coverage > 0.5f;
  view.sdf = signed_distance(view.mask);
  auto s = strip(30.0, 4.6, 0.15);
  const auto edges = mesh_edges(s.tri);
  SkinJacobian J;
  J.cols.resize(s.X.dim(0));
  J.vals.resize(s.X.dim(0));
  const double ca = std::cos(0.15), sa = std::sin(0.15);
  // Parameters: the left and right vertex columns move across the strip (px).
  const double px = kD / kF;
  for (std::size_t v = 0; v < s.X.dim(0); ++v) {
    J.cols[v] = {v % 3 == 0 ? 0 : v % 3 == 2 ? 1 : 2};
    J.vals[v] = {cv::Vec3d(ca * px, 0, sa * px)};
  }
  double left = 30.0 - 2.3, right = 30.0 + 2.3;
  for (int it = 0; it < 8; ++it) {
    NormalEquations ne(3);
    add_coverage_residuals(view, project_model(c, s.X, s.tri), s.tri, edges, &J, CoverageOptions{}, ne);
    Eigen::MatrixXd A = ne.A();
    A(2, 2) += 1;  // the middle column sees no outline
    const Eigen::VectorXd d = A.ldlt().solve(-ne.g());
    for (std::size_t v = 0; v < s.X.dim(0); ++v) {
      const double step = v % 3 == 0 ? d[0] : v % 3 == 2 ? d[1] : d[2];
      s.X(v, 0) += step * ca * px;
      s.X(v, 2) += step * sa * px;
    }
    left += d[0], right += d[1];
  }
  EXPECT_NEAR(left, true_left, 0.03);
  EXPECT_NEAR(right, true_right, 0.03);
}

namespace {
// A backlit 96 x 96 frame (level 200) darkened by 45 levels times the true coverage `truth` of
// the strips, plus seeded sensor noise of sigma 2.
Camera frame_camera() {
  Camera c = front_camera();
  c.width = c.height = 96;
  c.K(0, 2) = c.K(1, 2) = 47.5;  // strip(u0, ...) is centred on pixel (u0 + 16, 47.5)
  return c;
}
cv::Mat backlit_frame(const cv::Mat& truth) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0, 2);
  cv::Mat frame(truth.size(), CV_8U);
  for (int y = 0; y < frame.rows; ++y)
    for (int x = 0; x < frame.cols; ++x)
      frame.at<std::uint8_t>(y, x) = cv::saturate_cast<std::uint8_t>(200 - 45 * truth.at<float>(y, x) + noise(rng));
  return frame;
}
}  // namespace

TEST(CoverageResidual, SoftSegmentationOfTwoProngsKeepsTheGap) {
  // Two strips 3.4 px wide with a light gap of 1.2 px between them (the fork seen edge-on): the
  // pre-blurred detection merges them into one blob whose core runs along the gap, but the soft
  // segmentation must still read the gap as (nearly) uncovered.
  const Camera c = frame_camera();
  const auto s = merge(strip(30.2 - 2.3, 3.4, 0.12), strip(30.2 + 2.3, 3.4, 0.12));
  const cv::Mat truth = silhouette_coverage(c, s.X, s.tri, 16);
  const auto seg = segment_fin(backlit_frame(truth));
  double err = 0, gap = 0;
  int rows = 0;
  for (int y = 34; y < 62; ++y) {
    err += cv::sum(seg.coverage.row(y))[0] - cv::sum(truth.row(y))[0];
    // The gap's centre on this row: where the truth is least covered between the prongs.
    int x0 = 0;
    for (int x = 40; x < 53; ++x)
      if (truth.at<float>(y, x) < truth.at<float>(y, x0) || x0 == 0) x0 = x;
    gap += seg.coverage.at<float>(y, x0), ++rows;
  }
  EXPECT_LT(std::abs(err / rows), 0.3);  // mean width error, px (four edges)
  EXPECT_LT(gap / rows, 0.25);           // mean soft coverage at the gap's centre
}

TEST(CoverageResidual, SoftSegmentationAddsUpToTheStripWidth) {
  // A tilted strip 6.4 px wide.
  const Camera c = frame_camera();
  const double w = 6.4;
  const Strip s = strip(30.2, w, 0.12);
  const cv::Mat truth = silhouette_coverage(c, s.X, s.tri, 16);
  const auto seg = segment_fin(backlit_frame(truth));
  ASSERT_EQ(seg.coverage.type(), CV_32F);
  // Rows away from the strip's ends: coverage summed across a row is the strip's width across
  // the row, w / cos(tilt).
  double err = 0;
  int rows = 0;
  for (int y = 34; y < 62; ++y) {
    const double a = cv::sum(seg.coverage.row(y))[0], b = cv::sum(truth.row(y))[0];
    ASSERT_GT(b, w);
    err += a - b, ++rows;
  }
  EXPECT_LT(std::abs(err / rows), 0.08);  // mean width error, px
  EXPECT_LT(cv::norm(seg.coverage, truth, cv::NORM_L1) / (2 * 40), 0.25);  // per pixel of outline
}
