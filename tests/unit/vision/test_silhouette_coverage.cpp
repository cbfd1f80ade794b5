// Area-coverage silhouettes used to score the fit against the truth (silhouette_coverage.hpp):
// one sample per pixel is the pixel-centre mask of project_model, the coverage of a flat strip
// adds up to its projected area, a quarter-pixel shift of a two-pixel strip costs the IoU its
// true area fraction (a binary IoU sees nothing or a whole pixel column), and for binary maps
// the coverage IoU is the ordinary IoU.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "vision/silhouette_coverage.hpp"
#include "front_camera.hpp"
#include "vision/silhouette_residual.hpp"

using namespace finverse;
using namespace finverse::vision;
using finverse::vision::test::front_camera;
using finverse::vision::test::kD;
using finverse::vision::test::kF;

namespace {

// A rectangle in the plane y = 0 covering pixels [u0, u1] x [v0, v1] (pixel units).
NdArray<double> rectangle(double u0, double u1, double v0, double v1, NdArray<std::int32_t>* tri) {
  const Camera c = front_camera();
  auto X = [&](double u, double v) { return std::array<double, 2>{(u - c.K(0, 2)) * kD / kF, -(v - c.K(1, 2)) * kD / kF}; };
  NdArray<double> P({4, 3});
  const std::array<double, 2> q[4] = {X(u0, v0), X(u1, v0), X(u1, v1), X(u0, v1)};
  for (int i = 0; i < 4; ++i) P(i, 0) = q[i][0], P(i, 1) = 0, P(i, 2) = q[i][1];
  *tri = NdArray<std::int32_t>({2, 3}, {0, 1, 2, 0, 2, 3});
  return P;
}

}  // namespace

TEST(SilhouetteCoverage, OneSampleIsThePixelCentreMask) {
  NdArray<std::int32_t> tri;
  const auto P = rectangle(10.3, 30.6, 12.2, 40.9, &tri);
  const Camera c = front_camera();
  const cv::Mat one = silhouette_coverage(c, P, tri, 1);
  const cv::Mat mask = project_model(c, P, tri).mask;
  cv::Mat as8;
  one.convertTo(as8, CV_8U, 255);
  EXPECT_EQ(cv::countNonZero(as8 != mask), 0);
  EXPECT_THROW(silhouette_coverage(c, P, tri, 0), Error);
}

TEST(SilhouetteCoverage, AreaAndQuarterPixelShiftOfAThinStrip) {
  const Camera c = front_camera();
  NdArray<std::int32_t> tri;
  // A strip two pixels wide and 40 tall, its left edge a quarter pixel off a pixel boundary.
  const auto A = rectangle(20.25, 22.25, 10.0, 50.0, &tri);
  const auto B = rectangle(20.5, 22.5, 10.0, 50.0, &tri);  // a quarter pixel to the right
  const cv::Mat a = silhouette_coverage(c, A, tri, 4), b = silhouette_coverage(c, B, tri, 4);
  EXPECT_NEAR(cv::sum(a)[0], 80.0, 0.5);  // area in pixels
  // Area overlap 1.75 x 40 over the union 2.25 x 40.
  EXPECT_NEAR(coverage_iou(a, b), 1.75 / 2.25, 0.01);
  EXPECT_NEAR(coverage_iou(a, a), 1.0, 1e-12);
  // Binary maps: the ordinary IoU.
  const cv::Mat ma = project_model(c, A, tri).mask, mb = project_model(c, B, tri).mask;
  EXPECT_NEAR(coverage_iou(ma, mb), mask_iou(ma, mb), 1e-12);
  EXPECT_EQ(coverage_iou(cv::Mat::zeros(8, 8, CV_32F), cv::Mat::zeros(8, 8, CV_32F)), 1.0);
  EXPECT_THROW(coverage_iou(a, cv::Mat::zeros(8, 8, CV_32F)), Error);
}
