// The report's graded numbers on analytic inputs (tools/report): trailing-edge peak-to-peak
// (Fig. 14), the W-shape measures alpha1, alpha2, d1, d2 (Fig. 15(b)), mean and peak C_T
// (Fig. 16), the fitted-modulus scores (Fig. 11) and the met / missed / not available marks.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "report/fin_profiles.hpp"
#include "report/force_statistics.hpp"
#include "report/modulus_scores.hpp"
#include "report/motion_distance.hpp"
#include "report/score.hpp"
#include "report/trailing_edge.hpp"
#include "report/w_shape.hpp"

namespace finverse::report {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(WShape, AVShapedProfileGivesItsSlopeAndDepthOnBothHalves) {
  // y = k |z|: both edges lead by k h/2, the middle lags; alpha = atan(k) on each half.
  std::vector<double> z, y;
  const double k = 0.7, chord = 0.01;
  for (int i = 0; i <= 20; ++i) z.push_back(-0.01 + 0.001 * i), y.push_back(k * std::abs(z.back()));
  const auto w = w_shape(z, y, chord);
  EXPECT_NEAR(w.alpha1_deg, std::atan(k) * 180 / kPi, 1e-9);
  EXPECT_NEAR(w.alpha2_deg, std::atan(k) * 180 / kPi, 1e-9);
  EXPECT_NEAR(w.d1, k * 0.01 / chord, 1e-12);
  EXPECT_NEAR(w.d2, k * 0.01 / chord, 1e-12);
}

TEST(WShape, AnAsymmetricWMeasuresEachHalfFromItsTipToItsDeepestLag) {
  // Upper half: tip (z 1, y 1), deepest lag (z 0.5, y -0.2); lower half: tip (z -1, y 0.5),
  // lag (z -0.25, y -0.1). Mirrored in y (the other stroke) the measures are the same.
  const std::vector<double> z{-1, -0.75, -0.5, -0.25, 0, 0.25, 0.5, 0.75, 1};
  std::vector<double> y{0.5, 0.2, 0.0, -0.1, 0.0, -0.1, -0.2, 0.3, 1.0};
  for (int sign : {1, -1}) {
    std::vector<double> ys = y;
    for (double& v : ys) v *= sign;
    const auto w = w_shape(z, ys, 2.0);
    EXPECT_NEAR(w.d1, 1.2 / 2.0, 1e-12);
    EXPECT_NEAR(w.alpha1_deg, std::atan2(1.2, 0.5) * 180 / kPi, 1e-9);
    EXPECT_NEAR(w.d2, 0.6 / 2.0, 1e-12);
    EXPECT_NEAR(w.alpha2_deg, std::atan2(0.6, 0.75) * 180 / kPi, 1e-9);
  }
}

TEST(WShape, AFlatProfileHasNoWAndBadInputIsRefused) {
  const auto w = w_shape({0, 1, 2, 3, 4}, {0.3, 0.3, 0.3, 0.3, 0.3}, 1.0);
  EXPECT_EQ(w.d1, 0.0);
  EXPECT_EQ(w.d2, 0.0);
  EXPECT_EQ(w.alpha1_deg, 0.0);
  EXPECT_THROW(w_shape({0, 1}, {0, 1}, 1.0), Error);
  EXPECT_THROW(w_shape({0, 2, 1}, {0, 1, 2}, 1.0), Error);
}

TEST(TrailingEdge, PointsArePickedPerBandAndPeakToPeakOfASineIsTwiceItsAmplitude) {
  // A rectangle x in [0, 1], z in [0, 1.5] on a 11 x 16 grid: the picked points lie on x = 1.
  NdArray<double> rest({11 * 16, 3});
  for (int i = 0; i < 11; ++i)
    for (int j = 0; j < 16; ++j) rest(i * 16 + j, 0) = 0.1 * i, rest(i * 16 + j, 2) = 0.1 * j;
  const auto te = trailing_edge_points(rest);
  for (auto n : te) EXPECT_DOUBLE_EQ(rest(n, 0), 1.0);
  EXPECT_GE(rest(te[0], 2), 1.2);
  EXPECT_NEAR(rest(te[1], 2), 0.75, 0.08);
  EXPECT_LE(rest(te[2], 2), 0.3);
  // y = 0.4 sin(2 pi t) sampled over one period: peak-to-peak 0.8.
  const std::size_t nf = 40;
  NdArray<double> pts({nf, rest.dim(0), 3});
  for (std::size_t f = 0; f < nf; ++f)
    for (std::size_t v = 0; v < rest.dim(0); ++v) pts(f, v, 1) = 0.4 * std::sin(2 * kPi * double(f) / nf);
  EXPECT_NEAR(peak_to_peak(node_series(pts, te[0])), 0.8, 1e-12);
  EXPECT_EQ(midway_frame(node_series(pts, te[1])) % 20, 0u);  // the zero crossings
}

TEST(ForceStatistics, TimeWeightedMeanAndPeakOfACosine) {
  // C_T = 0.05 + 0.1 cos(2 pi t) over one period, unevenly sampled: mean 0.05, peak 0.15.
  std::vector<double> t, c;
  for (int i = 0; i <= 400; ++i) {
    const double s = double(i) / 400, ti = s * s;  // denser near t = 0
    t.push_back(ti), c.push_back(0.05 + 0.1 * std::cos(2 * kPi * ti));
  }
  const auto s = force_statistics(t, c);
  EXPECT_NEAR(s.mean, 0.05, 1e-4);
  EXPECT_NEAR(s.peak, 0.15, 1e-9);
  EXPECT_NEAR(s.minimum, -0.05, 1e-4);
  EXPECT_THROW(force_statistics({0, 1}, {1}), Error);
}

TEST(ModulusScores, MedianWorstIdentifiedAndMembraneAreGradedAgainstTheirGoals) {
  stage::Materials m;
  m.names = {"E_membrane", "E_ray1", "E_ray2", "E_ray3", "nu"};
  m.best = NdArray<double>({5}, {1.05e7, 1.0e9, 0.52e9, 3e8, 0.4});
  m.identified = NdArray<std::int32_t>({5}, {1, 1, 1, 0, 1});
  const std::map<std::string, double> truth{{"E_membrane", 1e7}, {"E_ray1", 1e9}, {"E_ray2", 0.5e9},
                                            {"E_ray3", 1e8}, {"nu", 0.4}};
  const auto scores = modulus_scores(modulus_rows(m, truth), "test");
  ASSERT_EQ(scores.size(), 3u);
  EXPECT_NEAR(*scores[0].value, 0.04, 1e-12);  // median of 0, 0.04, 2.0
  EXPECT_EQ(scores[0].status, Status::met);
  EXPECT_NEAR(*scores[1].value, 0.04, 1e-12);  // ray 3 (error 200 %) is not identified
  EXPECT_EQ(scores[1].status, Status::met);
  EXPECT_NEAR(*scores[2].value, 0.05, 1e-12);
  EXPECT_EQ(scores[2].status, Status::met);
  m.identified = NdArray<std::int32_t>({5}, {1, 1, 1, 1, 1});
  EXPECT_EQ(modulus_scores(modulus_rows(m, truth), "test")[1].status, Status::missed);
  m.identified = NdArray<std::int32_t>({5}, {1, 0, 0, 0, 1});
  EXPECT_EQ(modulus_scores(modulus_rows(m, truth), "test")[1].status, Status::not_available);
}

TEST(MotionDistance, AnOffsetMotionOnOtherFramesIsItsOffsetAfterInterpolation) {
  // a: 5 nodes moving y = t at times 0, 0.1, ..., 1.0; b: the same motion + 0.002 m in z at times
  // 0, 0.25, ..., 1.0 (linear in time: interpolation is exact); a's frames beyond 1.0 are skipped.
  const std::size_t nv = 5;
  NdArray<double> ta({12}), a({12, nv, 3}), tb({5}), b({5, nv, 3});
  for (std::size_t f = 0; f < 12; ++f) {
    ta(f) = 0.1 * double(f);
    for (std::size_t v = 0; v < nv; ++v) a(f, v, 0) = double(v), a(f, v, 1) = ta(f);
  }
  for (std::size_t f = 0; f < 5; ++f) {
    tb(f) = 0.25 * double(f);
    for (std::size_t v = 0; v < nv; ++v) b(f, v, 0) = double(v), b(f, v, 1) = tb(f), b(f, v, 2) = 0.002;
  }
  EXPECT_NEAR(mean_node_distance(ta, a, tb, b), 0.002, 1e-15);
  NdArray<double> tc({1}, {5.0});
  EXPECT_TRUE(std::isnan(mean_node_distance(tc, NdArray<double>({1, nv, 3}), tb, b)));
  EXPECT_THROW(mean_node_distance(ta, a, tb, NdArray<double>({5, nv + 1, 3})), Error);
}

TEST(Score, MetMissedAndNotAvailableAreMarked) {
  EXPECT_EQ(graded("a", 0.03, 0.03, "s").status, Status::met);
  EXPECT_EQ(graded("a", 0.031, 0.03, "s").status, Status::missed);
  EXPECT_EQ(graded("a", relative_difference(1, 0), 0.03, "s").status, Status::not_available);
  const auto j = to_json(unavailable("a", 0.1, "s", "needs fsi.h5"));
  EXPECT_EQ(j["status"], "not available");
  EXPECT_TRUE(j["value"].is_null());
  EXPECT_EQ(j["note"], "needs fsi.h5");
}

}  // namespace
}  // namespace finverse::report
