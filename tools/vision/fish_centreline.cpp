// The fish's centreline with the appendages ignored (see fish_centreline.hpp).
#include "vision/fish_centreline.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <opencv2/imgproc.hpp>

namespace finverse::vision {
namespace {

constexpr double kStep = 0.25;  // sampling along a slice (px)

struct Run {
  double lo, hi;
  double middle() const { return 0.5 * (lo + hi); }
};

// The runs of `m` (non-zero) along the line at + t n, t in [t0, t1]; runs less than `gap` apart
// are one.
std::vector<Run> runs_across(const cv::Mat& m, const cv::Point2d& at, const cv::Point2d& n, double t0, double t1,
                             double gap = 0) {
  std::vector<Run> runs;
  bool inside = false;
  for (double t = t0; t <= t1 + 1e-9; t += kStep) {
    const cv::Point2d q = at + t * n;
    const int x = static_cast<int>(std::lround(q.x)), y = static_cast<int>(std::lround(q.y));
    const bool on = x >= 0 && y >= 0 && x < m.cols && y < m.rows && m.at<std::uint8_t>(y, x) != 0;
    if (on && !inside && (runs.empty() || t - 0.5 * kStep - runs.back().hi > gap))
      runs.push_back({t - 0.5 * kStep, t + 0.5 * kStep});
    if (on) runs.back().hi = t + 0.5 * kStep;
    inside = on;
  }
  return runs;
}

// One slice across the axis: the silhouette's run through the fish and, where the core reaches,
// the core's run inside it.
struct Slice {
  double s = 0;
  Run fish{0, 0}, core{0, 0};
  bool on_core = false;
  bool clean() const { return on_core && fish.lo >= core.lo - kEdgePx && fish.hi <= core.hi + kEdgePx; }
};

// The run of `runs` nearest `previous` (NaN: the widest).
Run nearest(const std::vector<Run>& runs, double previous) {
  return *std::min_element(runs.begin(), runs.end(), [&](const Run& a, const Run& c) {
    if (std::isnan(previous)) return a.hi - a.lo > c.hi - c.lo;
    return std::abs(a.middle() - previous) < std::abs(c.middle() - previous);
  });
}

// The trunk's half-width at slice k from the clean slices around it: a least-squares quadratic in s
// through the clean slices within kWidthWindow slices either side (a line with fewer than five,
// the nearest clean slice's with fewer than two). NaN without any.
double half_width_at(const std::vector<Slice>& sl, std::size_t k) {
  std::vector<double> s, w;
  const std::size_t a = k > kWidthWindow ? k - kWidthWindow : 0, b = std::min(sl.size(), k + kWidthWindow + 1);
  for (std::size_t j = a; j < b; ++j)
    if (sl[j].clean()) s.push_back(sl[j].s - sl[k].s), w.push_back(0.5 * (sl[j].fish.hi - sl[j].fish.lo));
  if (s.empty()) return std::numeric_limits<double>::quiet_NaN();
  const int order = s.size() >= 5 ? 2 : (s.size() >= 2 ? 1 : 0);
  cv::Mat A(static_cast<int>(s.size()), order + 1, CV_64F), y(static_cast<int>(s.size()), 1, CV_64F), c;
  for (int i = 0; i < A.rows; ++i) {
    for (int p = 0; p <= order; ++p) A.at<double>(i, p) = std::pow(s[i], p);
    y.at<double>(i) = w[i];
  }
  cv::solve(A, y, c, cv::DECOMP_SVD);
  return c.at<double>(0);
}

}  // namespace

BodyCore body_core(const cv::Mat& mask) {
  if (cv::countNonZero(mask) == 0) return {};
  BodyCore out{cv::Mat::zeros(mask.size(), CV_8U), 0};
  const int pad = 2;
  cv::Rect box = cv::boundingRect(mask);
  box = cv::Rect(box.x - pad, box.y - pad, box.width + 2 * pad, box.height + 2 * pad) &
        cv::Rect(0, 0, mask.cols, mask.rows);
  const cv::Mat m = mask(box) != 0;
  cv::Mat depth;
  cv::distanceTransform(m, depth, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  double deepest = 0;
  cv::minMaxLoc(depth, nullptr, &deepest);
  out.half_width = deepest;
  const double r = kCoreFraction * deepest;
  cv::Mat opened;
  if (r < 1.5) {  // a silhouette this thin has no appendage to take off
    opened = m.clone();
  } else {
    const cv::Mat centres = depth >= r;  // where a disc of radius r fits
    cv::Mat reach;
    cv::distanceTransform(~centres, reach, cv::DIST_L2, cv::DIST_MASK_PRECISE);
    opened = (reach <= r) & m;
  }
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(opened, labels, stats, centroids, 8);
  int best = 0;
  for (int k = 1; k < n; ++k)
    if (best == 0 || stats.at<int>(k, cv::CC_STAT_AREA) > stats.at<int>(best, cv::CC_STAT_AREA)) best = k;
  if (best > 0) out.mask(box).setTo(255, labels == best);
  return out;
}

std::vector<cv::Point2d> fish_centreline(const cv::Mat& mask, const BodyCore& core, const cv::Point2d& origin,
                                         const cv::Point2d& u, double lo, double hi, int stations) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const cv::Point2d n(-u.y, u.x);
  std::vector<cv::Point> pts;
  cv::findNonZero(mask, pts);
  double t0 = 1e300, t1 = -1e300;
  for (const auto& p : pts) {
    const double t = (cv::Point2d(p) - origin).dot(n);
    t0 = std::min(t0, t - 1), t1 = std::max(t1, t + 1);
  }
  std::vector<cv::Point2d> out(stations, cv::Point2d(kNaN, kNaN));
  if (pts.empty()) return out;
  const double step = (hi - lo) / stations;
  const int per = std::clamp(static_cast<int>(std::lround(step)), 1, kSlicesPerStation);
  // The slices, head to tail, each run the one nearest the last slice's.
  std::vector<Slice> slices;
  std::vector<int> station_of;
  double previous = kNaN;
  for (int b = 0; b < stations; ++b)
    for (int j = 0; j < per; ++j) {
      Slice sl;
      sl.s = lo + (b + (j + 0.5) / per) * step;
      const cv::Point2d at = origin + sl.s * u;
      const auto fish = runs_across(mask, at, n, t0, t1, 0.5 * core.half_width);
      if (fish.empty()) continue;
      const auto in_core = core.mask.empty() ? std::vector<Run>{} : runs_across(core.mask, at, n, t0, t1);
      sl.on_core = !in_core.empty();
      if (sl.on_core) sl.core = nearest(in_core, previous);
      sl.fish = nearest(fish, sl.on_core ? sl.core.middle() : previous);
      previous = sl.on_core ? sl.core.middle() : sl.fish.middle();
      slices.push_back(sl), station_of.push_back(b);
    }
  // Each slice's middle: a clean slice's (no appendage on either side) and one whose silhouette
  // overhangs the core on both sides (the core's rounded ends; fins on both flanks) the middle of
  // the silhouette's run; one overhung on a single side, its clean edge and the trunk's half-width.
  std::vector<std::vector<double>> middles(stations);
  for (std::size_t k = 0; k < slices.size(); ++k) {
    const Slice& sl = slices[k];
    double middle = sl.fish.middle();
    const bool over_lo = sl.on_core && sl.fish.lo < sl.core.lo - kEdgePx,
               over_hi = sl.on_core && sl.fish.hi > sl.core.hi + kEdgePx;
    if (over_lo || over_hi) {
      const double w = half_width_at(slices, k);
      if (std::isnan(w)) {
      } else if (over_lo != over_hi) {
        middle = over_hi ? sl.fish.lo + w : sl.fish.hi - w;
      } else if (0.5 * (sl.core.hi - sl.core.lo) >= w - 2 * kEdgePx) {
        middle = sl.core.middle();  // fins on both flanks, the trunk's core whole between them
      }
    }
    middles[station_of[k]].push_back(middle);
  }
  for (int b = 0; b < stations; ++b) {
    auto& m = middles[b];
    if (m.empty()) continue;
    std::nth_element(m.begin(), m.begin() + m.size() / 2, m.end());
    out[b] = origin + (lo + (b + 0.5) * step) * u + m[m.size() / 2] * n;
  }
  return out;
}

}  // namespace finverse::vision
