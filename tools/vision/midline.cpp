// Midline, tail tip and tail-beat kinematics from silhouettes (see midline.hpp).
#include "vision/midline.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "core/error.hpp"
#include "vision/fish_centreline.hpp"

namespace finverse::vision {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// DFT magnitude of x (mean removed, Hann window) at frequency f (cycles per sample).
std::complex<double> dft(const std::vector<double>& x, double f) {
  std::complex<double> s = 0;
  const double n = static_cast<double>(x.size());
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double w = 0.5 - 0.5 * std::cos(2 * std::numbers::pi * (k + 0.5) / n);
    s += w * x[k] * std::polar(1.0, -2 * std::numbers::pi * f * static_cast<double>(k));
  }
  return s;
}

// Gaps (NaN) filled linearly, mean removed.
std::vector<double> filled(const std::vector<double>& x) {
  std::vector<double> y = x;
  const std::size_t n = y.size();
  std::size_t last = n;
  for (std::size_t k = 0; k < n; ++k) {
    if (std::isnan(y[k])) continue;
    if (last == n)
      for (std::size_t j = 0; j < k; ++j) y[j] = y[k];
    else
      for (std::size_t j = last + 1; j < k; ++j) y[j] = y[last] + (y[k] - y[last]) * double(j - last) / double(k - last);
    last = k;
  }
  if (last == n) return std::vector<double>(n, 0.0);
  for (std::size_t j = last + 1; j < n; ++j) y[j] = y[last];
  double mean = 0;
  for (double v : y) mean += v / static_cast<double>(n);
  for (double& v : y) v -= mean;
  return y;
}

}  // namespace

cv::Point2d refine_tail_tip(const cv::Mat& mask, const TipEvidence& e, const cv::Point2d& u, const cv::Point2d& fallback) {
  std::vector<cv::Point> pts;
  cv::findNonZero(mask, pts);
  if (pts.empty() || e.darkening.empty()) return fallback;
  const cv::Point2d n(-u.y, u.x);
  double hi = -1e300;
  for (const auto& p : pts) hi = std::max(hi, cv::Point2d(p).dot(u));
  double tlo = 1e300, thi = -1e300;
  for (const auto& p : pts)
    if (cv::Point2d(p).dot(u) >= hi - kTipWindowPx) tlo = std::min(tlo, cv::Point2d(p).dot(n)), thi = std::max(thi, cv::Point2d(p).dot(n));
  const auto on_mask = [&](const cv::Point2d& q) {
    const int x = static_cast<int>(std::lround(q.x)), y = static_cast<int>(std::lround(q.y));
    return x >= 0 && y >= 0 && x < mask.cols && y < mask.rows && mask.at<std::uint8_t>(y, x) != 0;
  };
  cv::Mat Db;  // the darkening as the segmentation's detection sees it
  if (e.blur_sigma > 0) cv::GaussianBlur(e.darkening, Db, cv::Size(0, 0), e.blur_sigma);
  else Db = e.darkening;
  const auto sample = [&](const cv::Mat& D, const cv::Point2d& q) {  // bilinear; 0 (background) outside the window
    const double x = q.x - e.origin.x, y = q.y - e.origin.y;
    const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
    if (x0 < 0 || y0 < 0 || x0 + 1 >= D.cols || y0 + 1 >= D.rows) return 0.0;
    const double fx = x - x0, fy = y - y0;
    return (1 - fy) * ((1 - fx) * D.at<float>(y0, x0) + fx * D.at<float>(y0, x0 + 1)) +
           fy * ((1 - fx) * D.at<float>(y0 + 1, x0) + fx * D.at<float>(y0 + 1, x0 + 1));
  };
  constexpr double ds = 0.05, dt = 0.25;  // sampling along and across the axis (px)
  const int ns = static_cast<int>(std::lround((kTipWindowPx + kTipReachPx + 1) / ds)) + 1;
  std::vector<double> d(ns), db(ns);
  std::vector<char> m(ns);
  double best = -1e300, best_t = 0;
  for (double t = tlo - 1; t <= thi + 1 + 1e-9; t += dt) {
    int last = -1;
    double peak = 0;
    for (int k = 0; k < ns; ++k) {
      const cv::Point2d q = (hi - kTipWindowPx + k * ds) * u + t * n;
      d[k] = sample(e.darkening, q), db[k] = sample(Db, q), m[k] = on_mask(q);
      if (m[k]) last = k;
    }
    if (last < 0) continue;
    // The fin seen beyond the mask: still detected (a sliver the rim rule left out).
    int end = last;
    while (end + 1 < ns && db[end + 1] > e.threshold && (end + 1 - last) * ds <= kTipReachPx) ++end;
    for (int k = std::max(0, end - static_cast<int>(std::lround(kTipLevelPx / ds))); k <= end; ++k) peak = std::max(peak, d[k]);
    if (peak < e.threshold) continue;
    const double half = 0.5 * peak;
    const auto s_at = [&](int k) { return hi - kTipWindowPx + k * ds; };
    int k = end;
    double s = s_at(last);  // below half from the mask's end on: the mask's own end
    if (d[k] >= half) {
      while (k + 1 < ns && d[k + 1] >= half && (k + 1 - last) * ds <= kTipReachPx) ++k;
      s = s_at(k);
      if (k + 1 < ns && d[k + 1] < half) s += ds * (d[k] - half) / (d[k] - d[k + 1]);
    } else {
      while (k > last && d[k] < half) --k;
      if (d[k] >= half) s = s_at(k) + ds * (d[k] - half) / (d[k] - d[k + 1]);
    }
    if (s > best) best = s, best_t = t;
  }
  return best > -1e300 ? best * u + best_t * n : fallback;
}

std::vector<MidlineFrame> extract_midlines(const std::vector<cv::Mat>& masks, int stations, cv::Point2d* axis_out,
                                           const std::vector<TipEvidence>* evidence) {
  if (evidence && evidence->size() != masks.size()) throw Error("midline: expected one tip evidence per mask");
  if (stations < 3) throw Error("midline: expected at least 3 stations");
  // The mean axis: principal axis of the union of all frames' pixels, relative to each frame's
  // centroid (the fish may translate).
  cv::Matx22d C = cv::Matx22d::zeros();
  std::vector<cv::Point2d> centroid(masks.size());
  std::vector<std::vector<cv::Point>> pts(masks.size());
  for (std::size_t i = 0; i < masks.size(); ++i) {
    cv::findNonZero(masks[i], pts[i]);
    if (pts[i].empty()) continue;
    cv::Point2d c(0, 0);
    for (const auto& p : pts[i]) c += cv::Point2d(p);
    centroid[i] = c * (1.0 / static_cast<double>(pts[i].size()));
    for (const auto& p : pts[i]) {
      const cv::Point2d d = cv::Point2d(p) - centroid[i];
      C += cv::Matx22d(d.x * d.x, d.x * d.y, d.x * d.y, d.y * d.y);
    }
  }
  cv::Mat evals, evecs;
  cv::eigen(cv::Mat(C), evals, evecs);
  cv::Point2d u(evecs.at<double>(0, 0), evecs.at<double>(0, 1));
  // Head: the half with more area over the record.
  double ahead = 0, behind = 0;
  for (std::size_t i = 0; i < masks.size(); ++i)
    for (const auto& p : pts[i]) ((cv::Point2d(p) - centroid[i]).dot(u) < 0 ? ahead : behind) += 1;
  if (behind > ahead) u = -u;  // u points from head to tail
  const cv::Point2d n(-u.y, u.x);
  if (axis_out) *axis_out = u;

  std::vector<MidlineFrame> out(masks.size());
  std::vector<double> length(masks.size(), 0.0);  // the midline's arc length to the tip (px)
  for (std::size_t i = 0; i < masks.size(); ++i) {
    auto& f = out[i];
    f.reason = "no fish";
    if (pts[i].size() < 8) continue;
    double lo = 1e300, hi = -1e300;
    for (const auto& p : pts[i]) {
      const double s = (cv::Point2d(p) - centroid[i]).dot(u);
      lo = std::min(lo, s), hi = std::max(hi, s);
    }
    if (hi - lo < stations) {
      f.reason = "the fish is shorter than the stations (px)";
      continue;
    }
    double tip_sum = 0, tip_n = 0;
    for (const auto& p : pts[i]) {
      const cv::Point2d d = cv::Point2d(p) - centroid[i];
      if (d.dot(u) >= hi - 1.5) tip_sum += d.dot(n), tip_n += 1;  // the last pixel and a half on the axis
    }
    f.points = fish_centreline(masks[i], body_core(masks[i]), centroid[i], u, lo, hi, stations);
    f.tip = centroid[i] + (hi + 0.5) * u + (tip_sum / tip_n) * n;
    if (evidence) f.tip = refine_tail_tip(masks[i], (*evidence)[i], u, f.tip);
    f.centroid = centroid[i];
    f.valid = true;
    f.reason.clear();
    cv::Point2d last(kNaN, kNaN);
    for (const auto& p : f.points)
      if (!std::isnan(p.x)) {
        if (!std::isnan(last.x)) length[i] += cv::norm(p - last);
        last = p;
      }
    length[i] += std::isnan(last.x) ? 0.0 : cv::norm(f.tip - last);
  }
  // A silhouette much shorter along its own midline than the record's median has lost its tail
  // (the fin too faint to segment): the fish is not whole, the frame not measured. Along the
  // midline, not the axis: a fish that bends or turns keeps its length.
  std::vector<double> lengths;
  for (double l : length)
    if (l > 0) lengths.push_back(l);
  if (!lengths.empty()) {
    std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
    const double median = lengths[lengths.size() / 2];
    for (std::size_t i = 0; i < masks.size(); ++i)
      if (out[i].valid && length[i] < (1 - kLostFinFraction) * median) {
        out[i].valid = false, out[i].lost_fin = true;
        out[i].reason = "the silhouette ends short of the fish's length (the tail lost)";
      }
  }
  return out;
}

TailBeat tail_beat(const std::vector<MidlineFrame>& m, const cv::Point2d& axis, double fps) {
  TailBeat r;
  r.axis = axis;
  const cv::Point2d n(-axis.y, axis.x);
  const std::size_t nf = m.size();
  if (nf < 8) throw Error("tail beat: need at least 8 frames, got " + std::to_string(nf));
  // Lateral positions across the axis from each frame's centroid (the fish's own drift across
  // the axis is removed with it).
  r.tip_lateral_px.assign(nf, kNaN);
  for (std::size_t i = 0; i < nf; ++i)
    if (m[i].valid) r.tip_lateral_px[i] = (m[i].tip - m[i].centroid).dot(n);
  const auto y = filled(r.tip_lateral_px);
  double mean = 0;
  std::size_t nv = 0;
  for (double v : r.tip_lateral_px)
    if (!std::isnan(v)) mean += v, ++nv;
  if (nv < 8) throw Error("tail beat: the fish was found in only " + std::to_string(nv) + " frames");
  mean /= static_cast<double>(nv);
  for (double& v : r.tip_lateral_px)
    if (!std::isnan(v)) v -= mean;
  // Frequency: the DFT peak on a fine grid above one cycle per record, refined parabolically.
  const double N = static_cast<double>(nf);
  double best_f = 0, best = -1;
  for (double f = 1.0 / N; f <= 0.5; f += 0.05 / N) {
    const double a = std::abs(dft(y, f));
    if (a > best) best = a, best_f = f;
  }
  {
    const double h = 0.05 / N;
    const double a = std::abs(dft(y, best_f - h)), b = best, c = std::abs(dft(y, best_f + h));
    const double den = a - 2 * b + c;
    if (den < 0) best_f += 0.5 * h * (a - c) / den;
  }
  r.frequency_hz = best_f * fps;
  // The lateral reference: the centroid averaged over one beat (the body's own wobble at the beat
  // frequency averages out; a fish drifting across the axis is followed).
  std::vector<double> cy(nf, kNaN), ref(nf, kNaN);
  for (std::size_t i = 0; i < nf; ++i)
    if (m[i].valid) cy[i] = m[i].centroid.dot(n);
  {
    const auto c = filled(cy);
    double cmean = 0;
    std::size_t cn = 0;
    for (double v : cy)
      if (!std::isnan(v)) cmean += v, ++cn;
    cmean /= static_cast<double>(cn);
    // Whole beats only: within half a beat of the record's ends, where the window would be cut
    // short and take part of a swing, the nearest whole window's mean holds.
    const int half = std::max(1, static_cast<int>(std::lround(0.5 / best_f)));
    const int last = static_cast<int>(nf) - 1;
    const bool whole = last >= 2 * half;
    for (std::size_t i = 0; i < nf; ++i) {
      const int centre = whole ? std::clamp(static_cast<int>(i), half, last - half) : static_cast<int>(i);
      double sum = 0;
      int k = 0;
      for (int j = centre - half; j <= centre + half; ++j)
        if (j >= 0 && j <= last) sum += c[static_cast<std::size_t>(j)], ++k;
      ref[i] = cmean + sum / k;
    }
  }
  for (std::size_t i = 0; i < nf; ++i)
    if (m[i].valid) r.tip_lateral_px[i] = m[i].tip.dot(n) - ref[i];
  const auto yt = filled(r.tip_lateral_px);
  // Amplitude: half the peak-to-peak excursion in every whole beat, averaged.
  const double period = 1 / best_f;  // frames
  double sum = 0;
  for (double start = 0; start + period <= N + 1e-9; start += period) {
    double lo = 1e300, hi = -1e300;
    for (std::size_t k = static_cast<std::size_t>(std::ceil(start)); k < nf && k < start + period; ++k)
      lo = std::min(lo, yt[k]), hi = std::max(hi, yt[k]);
    sum += 0.5 * (hi - lo), ++r.beats;
  }
  r.amplitude_px = r.beats > 0 ? sum / r.beats : kNaN;
  // Wavelength: the phase of each posterior station's lateral excursion at the beat frequency.
  const std::size_t ns = m[0].points.size();
  std::vector<double> s_px, phase;
  double prev = 0;
  for (std::size_t b = ns / 2; b < ns; ++b) {
    std::vector<double> lat(nf, kNaN);
    double along = 0;
    int na = 0;
    for (std::size_t i = 0; i < nf; ++i)
      if (m[i].valid && !std::isnan(m[i].points[b].x)) {
        lat[i] = m[i].points[b].dot(n) - ref[i];
        along += (m[i].points[b] - m[i].points[0]).dot(axis), ++na;
      }
    if (na < 8) continue;
    double ph = std::arg(dft(filled(lat), best_f));
    if (!phase.empty()) ph += 2 * std::numbers::pi * std::round((prev - ph) / (2 * std::numbers::pi));  // unwrap
    prev = ph;
    phase.push_back(ph), s_px.push_back(along / na);
  }
  if (phase.size() >= 3) {
    double ms = 0, mp = 0;
    for (std::size_t k = 0; k < phase.size(); ++k) ms += s_px[k], mp += phase[k];
    ms /= phase.size(), mp /= phase.size();
    double sxy = 0, sxx = 0;
    for (std::size_t k = 0; k < phase.size(); ++k) sxy += (s_px[k] - ms) * (phase[k] - mp), sxx += (s_px[k] - ms) * (s_px[k] - ms);
    const double slope = sxy / sxx;  // rad per px
    r.wavelength_px = std::abs(slope) > 0 ? 2 * std::numbers::pi / std::abs(slope) : kNaN;
  } else {
    r.wavelength_px = kNaN;
  }
  return r;
}

}  // namespace finverse::vision
