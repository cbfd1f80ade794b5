// Peduncle cut between the body and the caudal fin (see fin_separation.hpp).
#include "vision/fin_separation.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "vision/camera.hpp"

namespace finverse::vision {
namespace {

// The largest 8-connected component of `mask`.
cv::Mat largest_component(const cv::Mat& mask) {
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  int best = 0, area = 0;
  for (int l = 1; l < n; ++l)
    if (stats.at<int>(l, cv::CC_STAT_AREA) > area) area = stats.at<int>(l, cv::CC_STAT_AREA), best = l;
  return best > 0 ? cv::Mat(labels == best) : cv::Mat(cv::Mat::zeros(mask.size(), CV_8U));
}

}  // namespace

FinCut separate_caudal_fin(const cv::Mat& mask, const FinCutOptions& o, const cv::Vec3d* fin_side) {
  FinCut out;
  out.fin = mask.clone();
  std::vector<cv::Point> pts;
  cv::findNonZero(mask, pts);
  if (pts.size() < 16) return out;
  // Principal axis of the blob: the midline's direction.
  cv::Mat data(static_cast<int>(pts.size()), 2, CV_64F);
  for (std::size_t i = 0; i < pts.size(); ++i) data.at<double>(static_cast<int>(i), 0) = pts[i].x, data.at<double>(static_cast<int>(i), 1) = pts[i].y;
  const cv::PCA pca(data, cv::noArray(), cv::PCA::DATA_AS_ROW);
  const cv::Point2d c(pca.mean.at<double>(0), pca.mean.at<double>(1));
  cv::Point2d u(pca.eigenvectors.at<double>(0, 0), pca.eigenvectors.at<double>(0, 1));
  std::vector<double> s(pts.size());
  double lo = 1e300, hi = -1e300;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    s[i] = (pts[i].x - c.x) * u.x + (pts[i].y - c.y) * u.y;
    lo = std::min(lo, s[i]), hi = std::max(hi, s[i]);
  }
  const int nb = std::max(8, o.bins);
  const double len = hi - lo + 1, bw = len / nb;
  if (bw < 1) return out;  // too short to profile
  // Width = area per unit length, smoothed over three bins.
  std::vector<double> area(nb, 0.0), w(nb, 0.0);
  for (double si : s) {  // each pixel shared between its two nearest bins: no aliasing
    const double pos = std::clamp((si - lo) / bw - 0.5, 0.0, nb - 1.0);
    const int b0 = std::min(nb - 2, static_cast<int>(pos));
    area[b0] += 1 - (pos - b0), area[b0 + 1] += pos - b0;
  }
  for (int b = 0; b < nb; ++b) {
    double sum = 0;
    int n = 0;
    for (int d = -1; d <= 1; ++d)
      if (b + d >= 0 && b + d < nb) sum += area[b + d], ++n;
    w[b] = sum / n / bw;
  }
  // The peduncle: the deepest waist, the bin whose width is smallest against the widest part on
  // either side of it (a fin alone, widening from its root, or a tapering body has none). The
  // body is the side with more area (the caudal fin may be taller than the body is deep).
  std::vector<double> left(nb), right(nb);
  for (int b = 0; b < nb; ++b) left[b] = std::max(w[b], b > 0 ? left[b - 1] : 0.0);
  for (int b = nb - 1; b >= 0; --b) right[b] = std::max(w[b], b + 1 < nb ? right[b + 1] : 0.0);
  int ped = -1;
  double deepest = 1;
  for (int b = 1; b + 1 < nb; ++b) {
    const double ratio = std::min(left[b - 1], right[b + 1]) / std::max(w[b], 1e-9);
    if (ratio > deepest) deepest = ratio, ped = b;
  }
  if (ped < 0) return out;
  double area_low = 0, area_high = 0;
  for (int b = 0; b < nb; ++b) (b < ped ? area_low : area_high) += b == ped ? 0 : area[b];
  int dir = area_low >= area_high ? 1 : -1;  // towards the tail
  if (fin_side) {  // the calibration knows: the tail is the end on the fin's side of the root plane
    const cv::Vec3d& l = *fin_side;
    const cv::Point2d a = c + lo * u, b = c + hi * u;
    dir = l[0] * b.x + l[1] * b.y >= l[0] * a.x + l[1] * a.y ? 1 : -1;
  }
  // The fin begins where the peduncle ends: the tailmost bin of the waist (within 15 % of its
  // narrowest), where the width starts to grow.
  while (ped + 2 * dir >= 0 && ped + 2 * dir < nb && w[ped + dir] <= 1.15 * w[ped]) ped += dir;
  out.peduncle_px = w[ped];
  out.body_px = dir > 0 ? left[ped - 1] : right[ped + 1];
  out.fin_px = dir > 0 ? right[ped + 1] : left[ped - 1];
  if (out.body_px < o.body_ratio * out.peduncle_px || out.fin_px < o.fin_ratio * out.peduncle_px) return out;
  const double s_cut = lo + (ped + 0.5) * bw;
  out.at = c + s_cut * u;
  out.tailward = dir > 0 ? u : -u;
  cv::Mat fin_mask = cv::Mat::zeros(mask.size(), CV_8U);
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (dir > 0 ? s[i] > s_cut : s[i] < s_cut) fin_mask.at<std::uint8_t>(pts[i]) = 255;
  out.fin = largest_component(fin_mask);
  out.cut = cv::countNonZero(out.fin) > 0;
  if (!out.cut) out.fin = mask.clone();
  return out;
}

cv::Mat fin_region_mask(const cv::Mat& mask, const cv::Rect& region) {
  cv::Mat out = cv::Mat::zeros(mask.size(), CV_8U);
  const cv::Rect r = region & cv::Rect(0, 0, mask.cols, mask.rows);
  if (r.area() > 0) mask(r).copyTo(out(r));
  return out;
}

bool root_plane_line(const Camera& camera, double chord, cv::Vec3d& line) {
  const auto R = camera.rotation();
  const cv::Vec3d axis(R(2, 0), R(2, 1), R(2, 2));
  if (std::abs(axis[0]) > 0.5) return false;  // within 60 degrees of x: the plane is seen face-on
  // Two points of the plane across the view (x cross axis lies in it) and one upstream.
  const cv::Vec3d w = cv::normalize(cv::Vec3d(1, 0, 0).cross(axis));
  // A fiftieth of a chord upstream of the root: blur and the rays' thickness spread the fin's
  // own root a little past x = 0 (measured: docs/studies/footage_inputs.md).
  const cv::Vec3d o(-0.02 * chord, 0, 0);
  const cv::Point2d p = camera.project(o), q = camera.project(o + chord * w), body = camera.project({-chord, 0, 0});
  cv::Point2d n(-(q - p).y, (q - p).x);
  const double len = std::hypot(n.x, n.y);
  if (!(len > 1e-9)) return false;
  n *= 1 / len;
  line = {n.x, n.y, -n.dot(p)};
  if (n.dot(body) + line[2] > 0) line = -line;  // positive on the fin's side
  return true;
}

cv::Mat fin_side_mask(const cv::Mat& mask, const cv::Vec3d& line) {
  cv::Mat out = mask.clone();
  for (int y = 0; y < out.rows; ++y) {
    auto* m = out.ptr<std::uint8_t>(y);
    for (int x = 0; x < out.cols; ++x)
      if (m[x] && line[0] * x + line[1] * y + line[2] <= 0) m[x] = 0;
  }
  return out;
}

}  // namespace finverse::vision
