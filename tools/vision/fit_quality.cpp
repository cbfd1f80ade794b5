// Per-frame flags and the verdict on a 3-D fit (see fit_quality.hpp).
#include "vision/fit_quality.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace finverse::vision {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

std::string fmt(const char* f, double a, double b = 0) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, a, b);
  return buf;
}

}  // namespace

bool FitVerdict::flagged() const {
  return std::any_of(flags.begin(), flags.end(), [](std::uint8_t f) { return f != 0; });
}

FitVerdict judge_fit(const std::vector<FrameQuality>& frames, const std::vector<std::string>& views,
                     const FitQualityOptions& o) {
  FitVerdict out;
  const std::size_t nf = frames.size(), nview = views.size();
  out.flags.assign(nf, 0);
  std::size_t few = 0;
  std::vector<double> worst_iou;
  std::vector<std::vector<double>> ratio(nview);
  std::vector<std::size_t> shown(nview, 0);
  double drift = 0;
  std::size_t drift_at = 0;
  for (std::size_t i = 0; i < nf; ++i) {
    const auto& f = frames[i];
    auto& flag = out.flags[i];
    int valid = 0;
    double worst = 1;
    for (std::size_t v = 0; v < nview; ++v) {
      if (f.doubt[v]) flag |= kSegmentationDoubt;
      if (!f.valid[v]) continue;
      ++valid, ++shown[v];
      worst = std::min(worst, f.iou[v]);
      if (f.iou[v] < o.min_iou) flag |= kLowIoU;
      ratio[v].push_back(f.area_ratio[v]);
      if (!(f.area_ratio[v] <= o.max_area_ratio && f.area_ratio[v] >= 1 / o.max_area_ratio)) flag |= kScaleMismatch;
    }
    if (valid < o.min_views) flag |= kFewViews, ++few;
    if (valid > 0) worst_iou.push_back(worst);
    if (o.max_root_drift > 0 && f.root_drift > o.max_root_drift) flag |= kRootDrift;
    if (f.root_drift > drift) drift = f.root_drift, drift_at = i;
  }
  auto listed = [&] {
    std::string s;
    for (std::size_t v = 0; v < nview; ++v)
      if (shown[v] > 0) s += (s.empty() ? "'" : ", '") + views[v] + "'";
    return s.empty() ? std::string("none") : s;
  };
  if (2 * few > nf) {
    out.failure = "the views cannot constrain the 3-D fit: in " + std::to_string(few) + " of " + std::to_string(nf) +
                  " frames fewer than " + std::to_string(o.min_views) + " views show the fin (views with the fin: " + listed() +
                  "); one view leaves its depth free (use two views or more, or the 2-D single-view mode)";
    return out;
  }
  for (std::size_t v = 0; v < nview; ++v) {
    const double r = median(ratio[v]);
    if (!ratio[v].empty() && !(r <= o.max_area_ratio && r >= 1 / o.max_area_ratio)) {
      out.failure = "the template's scale cannot match the silhouettes: in view '" + views[v] + "' the fitted fin's area is " +
                    fmt("%.2f", r) + " times the segmented one (median over frames; expected within a factor " +
                    fmt("%g", o.max_area_ratio) + "): check the template's size (--chord, --template) and the cameras' scale";
      return out;
    }
  }
  const double iou = median(worst_iou);
  if (!worst_iou.empty() && !(iou >= o.min_iou)) {
    out.failure = "the fit does not cover the fin: the worst view's silhouette IoU is " + fmt("%.3f", iou) +
                  " (median over frames; expected >= " + fmt("%g", o.min_iou) + ")";
    return out;
  }
  if (o.max_root_drift > 0 && drift > o.max_root_drift) {
    out.failure = "the views do not hold the fin in place: its root drifted " + fmt("%.2f", drift) + " chords from the first frame's (frame " +
                  std::to_string(frames[drift_at].frame) + "; limit " + fmt("%g", o.max_root_drift) + " chords)";
    return out;
  }
  return out;
}

}  // namespace finverse::vision
