// The fish's body behind the caudal fin for realistic virtual footage (issue 35, item 8).
#include "vision/fish_body.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.hpp"

namespace finverse::vision {
namespace {

constexpr int kFanRays = 12;  // triangles per pectoral fan

// Cross-section size along the body, u = 0 at the snout .. 1 at the peduncle: an elliptic nose up
// to the widest section at u = 0.4, then a cosine taper to the peduncle.
double profile(double u, double peak, double peduncle) {
  constexpr double kWidest = 0.4;
  if (u <= kWidest) return peak * std::sqrt(std::max(0.0, 1 - std::pow((kWidest - u) / kWidest, 2)));
  return peduncle + (peak - peduncle) * 0.5 * (1 + std::cos(std::numbers::pi * (u - kWidest) / (1 - kWidest)));
}

}  // namespace

FishBody::FishBody(const FinSurface& fin, const FishBodyOptions& options) : fin_(fin), o_(options) {
  if (!(o_.length > 0)) throw Error("--body-length: expected > 0 chords");
  if (!(o_.max_depth > 0) || !(o_.max_width > 0)) throw Error("--body-depth/--body-width: expected > 0 chords");
  if (!(o_.level >= 0 && o_.level <= 1)) throw Error("--body-level: expected a grey level in [0, 1]");
  if (o_.stations < 4 || o_.sides < 8) throw Error("fish body: at least 4 stations and 8 sides");
  if (!(o_.head_motion >= 0 && o_.head_motion <= 1)) throw Error("--body-head-motion: expected a fraction in [0, 1]");
  double x0 = 0, z0 = 0, zmin = 1e300, zmax = -1e300;
  for (std::size_t i = 0; i < fin.size(); ++i)
    if (fin.s[i] == 0) {
      root_.push_back(i);
      x0 += fin.rest(i, 0), z0 += fin.rest(i, 2);
      zmin = std::min(zmin, fin.rest(i, 2)), zmax = std::max(zmax, fin.rest(i, 2));
    }
  if (root_.empty()) throw Error("fish body: the fin surface has no root vertices");
  x0 /= static_cast<double>(root_.size()), z0 /= static_cast<double>(root_.size());
  const double c = fin.chord;
  const double ped_depth = o_.peduncle_depth * (zmax - zmin), ped_width = o_.peduncle_width * c;
  if (ped_depth > o_.max_depth * c || ped_width > o_.max_width * c)
    throw Error("--body-depth/--body-width: the body must be at least as deep and wide as its peduncle (" +
                std::to_string(ped_depth / c) + " c deep, " + std::to_string(o_.peduncle_width) + " c wide)");

  const int ns = o_.stations, nr = o_.sides;
  const std::size_t nb = 2 + static_cast<std::size_t>(ns) * nr;
  rest_ = NdArray<double>({nb, 3});
  auto share = [&](double u) { return o_.head_motion + (1 - o_.head_motion) * u * u; };
  envelope_.assign(nb, share(0));
  envelope_[nb - 1] = 1;
  rest_(0, 0) = x0 - o_.length * c, rest_(0, 1) = 0, rest_(0, 2) = z0;  // snout
  for (int i = 1; i <= ns; ++i) {
    const double u = static_cast<double>(i) / ns;
    const double half_depth = 0.5 * profile(u, o_.max_depth * c, ped_depth);
    const double half_width = 0.5 * profile(u, o_.max_width * c, ped_width);
    for (int k = 0; k < nr; ++k) {
      const double a = 2 * std::numbers::pi * k / nr;
      const std::size_t v = 1 + static_cast<std::size_t>(i - 1) * nr + k;
      rest_(v, 0) = x0 - (1 - u) * o_.length * c;
      rest_(v, 1) = half_width * std::cos(a);
      rest_(v, 2) = z0 + half_depth * std::sin(a);
      envelope_[v] = share(u);
    }
  }
  rest_(nb - 1, 0) = x0, rest_(nb - 1, 1) = 0, rest_(nb - 1, 2) = z0;  // centre of the peduncle's end
  std::vector<std::int32_t> t;
  auto ring = [&](int i, int k) { return static_cast<std::int32_t>(1 + (i - 1) * nr + (k % nr)); };
  for (int k = 0; k < nr; ++k) t.insert(t.end(), {0, ring(1, k), ring(1, k + 1)});
  for (int i = 1; i < ns; ++i)
    for (int k = 0; k < nr; ++k)
      t.insert(t.end(), {ring(i, k), ring(i + 1, k), ring(i + 1, k + 1), ring(i, k), ring(i + 1, k + 1), ring(i, k + 1)});
  for (int k = 0; k < nr; ++k) t.insert(t.end(), {static_cast<std::int32_t>(nb - 1), ring(ns, k + 1), ring(ns, k)});
  trunk_ = nb;
  if (o_.pectoral_length > 0) add_pectoral_fins(t);
  triangles_ = NdArray<std::int32_t>({t.size() / 3, 3});
  triangles_.data = t;
}

// Each fan: its hinge, then the tips of kFanRays + 1 rays from the flank to the leading ray. The
// hinge sits just inside the flank at mid-depth, so the fin's base is hidden in the body.
void FishBody::add_pectoral_fins(std::vector<std::int32_t>& t) {
  const double u = o_.pectoral_station;
  if (!(u > 0 && u < 1)) throw Error("--pectoral-station: expected a fraction of the body's length in (0, 1)");
  if (!(o_.pectoral_open_min >= 0 && o_.pectoral_open_min < o_.pectoral_open_max && o_.pectoral_open_max <= 120))
    throw Error("--pectoral-open: expected 0 <= closed < open <= 120 degrees");
  if (!(o_.pectoral_frequency >= 0)) throw Error("--pectoral-frequency: expected >= 0 Hz");
  if (!(o_.pectoral_level >= 0 && o_.pectoral_level <= 1))
    throw Error("--pectoral-level: expected a grey level in [0, 1]");
  const double c = fin_.chord;
  const double x0 = rest_(trunk_ - 1, 0), z0 = rest_(trunk_ - 1, 2);
  const double half_width = 0.5 * profile(u, o_.max_width * c, o_.peduncle_width * c);
  pectoral_envelope_ = o_.head_motion + (1 - o_.head_motion) * u * u;
  for (int side = 0; side < 2; ++side) {
    const auto first = static_cast<std::int32_t>(trunk_ + side * (kFanRays + 2));
    hinge_[side] = cv::Vec3d(x0 - (1 - u) * o_.length * c, (side == 0 ? -0.85 : 0.85) * half_width, z0);
    for (int j = 0; j < kFanRays; ++j) t.insert(t.end(), {first, first + 1 + j, first + 2 + j});
  }
}

double FishBody::pectoral_opening(int side, double t) const {
  const double phase = 2 * std::numbers::pi * o_.pectoral_frequency * t + (side == 0 ? 0.0 : std::numbers::pi);
  const double open =
      o_.pectoral_open_min + (o_.pectoral_open_max - o_.pectoral_open_min) * 0.5 * (1 - std::cos(phase));
  return open * std::numbers::pi / 180;
}

NdArray<double> FishBody::place(const NdArray<double>& pos, double t) const {
  if (pos.rank() != 2 || pos.dim(0) != fin_.size() || pos.dim(1) != 3) throw Error("fish body: positions do not match the fin");
  double d[3] = {0, 0, 0};
  for (std::size_t i : root_)
    for (int k = 0; k < 3; ++k) d[k] += pos(i, k) - fin_.rest(i, k);
  for (auto& dk : d) dk /= static_cast<double>(root_.size());
  const std::size_t fans = o_.pectoral_length > 0 ? 2 * (kFanRays + 2) : 0;
  NdArray<double> out({trunk_ + fans, 3});
  for (std::size_t v = 0; v < trunk_; ++v) {
    out(v, 0) = rest_(v, 0) + d[0];
    out(v, 1) = rest_(v, 1) + envelope_[v] * d[1];
    out(v, 2) = rest_(v, 2) + envelope_[v] * d[2];
  }
  for (int side = 0; side < 2 && fans > 0; ++side) {
    const std::size_t first = trunk_ + side * (kFanRays + 2);
    const cv::Vec3d h = hinge_[side] + cv::Vec3d(d[0], pectoral_envelope_ * d[1], pectoral_envelope_ * d[2]);
    const double closed = o_.pectoral_open_min * std::numbers::pi / 180, open = pectoral_opening(side, t);
    const double outward = side == 0 ? -1 : 1, length = o_.pectoral_length * fin_.chord;
    for (int k = 0; k < 3; ++k) out(first, k) = h[k];
    for (int j = 0; j <= kFanRays; ++j) {
      const double f = static_cast<double>(j) / kFanRays;
      const double phi = closed + (open - closed) * f, r = length * (0.8 + 0.2 * f);  // the leading ray longest
      out(first + 1 + j, 0) = h[0] + r * std::cos(phi);  // rays point tailward (+x) and out
      out(first + 1 + j, 1) = h[1] + outward * r * std::sin(phi);
      out(first + 1 + j, 2) = h[2];
    }
  }
  return out;
}

NdArray<double> FishBody::axis(const NdArray<double>& pos) const {
  const auto X = place(pos);
  const int ns = o_.stations, nr = o_.sides;
  NdArray<double> a({static_cast<std::size_t>(ns) + 2, 3});
  for (int k = 0; k < 3; ++k) a(0, k) = X(0, k), a(ns + 1, k) = X(trunk_ - 1, k);
  for (int i = 1; i <= ns; ++i)
    for (int k = 0; k < 3; ++k) {
      double sum = 0;
      for (int j = 0; j < nr; ++j) sum += X(1 + static_cast<std::size_t>(i - 1) * nr + j, k);
      a(i, k) = sum / nr;
    }
  return a;
}

OpaqueLayer FishBody::rasterize(const Camera& cam, const NdArray<double>& fin_positions, int S, double time) const {
  const int W = cam.width * S, H = cam.height * S;
  OpaqueLayer layer{cv::Mat(H, W, CV_32F, cv::Scalar(std::numeric_limits<float>::infinity())), cv::Mat(H, W, CV_32F, cv::Scalar(0))};
  const auto X = place(fin_positions, time);
  const std::size_t nb = X.dim(0), nt = triangles_.dim(0);
  auto P = [&](std::int32_t i) { return cv::Vec3d(X(i, 0), X(i, 1), X(i, 2)); };
  std::vector<cv::Vec3d> normal(nb, cv::Vec3d(0, 0, 0));
  for (std::size_t t = 0; t < nt; ++t) {
    const auto a = triangles_(t, 0), b = triangles_(t, 1), c = triangles_(t, 2);
    const cv::Vec3d n = (P(b) - P(a)).cross(P(c) - P(a));
    for (auto v : {a, b, c}) normal[v] += n;
  }
  const cv::Vec3d eye = cam.center();
  std::vector<cv::Point2d> xy(nb);
  std::vector<double> depth(nb), level(nb);
  for (std::size_t i = 0; i < nb; ++i) {
    const auto p = cam.project(P(static_cast<std::int32_t>(i)), &depth[i]);
    xy[i] = {(p.x + 0.5) * S - 0.5, (p.y + 0.5) * S - 0.5};  // sample coordinates
    const double nn = cv::norm(normal[i]);
    const cv::Vec3d l = cv::normalize(eye - P(static_cast<std::int32_t>(i)));
    level[i] =
        (i < trunk_ ? o_.level : o_.pectoral_level) * (0.45 + 0.55 * (nn > 0 ? std::abs(normal[i].dot(l)) / nn : 1.0));
  }
  for (std::size_t t = 0; t < nt; ++t) {
    const std::int32_t v[3] = {triangles_(t, 0), triangles_(t, 1), triangles_(t, 2)};
    if (depth[v[0]] <= 0 || depth[v[1]] <= 0 || depth[v[2]] <= 0) continue;
    auto edge = [&](int a, int b, double px, double py) {
      return (xy[v[b]].x - xy[v[a]].x) * (py - xy[v[a]].y) - (xy[v[b]].y - xy[v[a]].y) * (px - xy[v[a]].x);
    };
    const double area = edge(0, 1, xy[v[2]].x, xy[v[2]].y);
    if (area == 0) continue;
    const int x0 = std::max(0, static_cast<int>(std::ceil(std::min({xy[v[0]].x, xy[v[1]].x, xy[v[2]].x}))));
    const int x1 = std::min(W - 1, static_cast<int>(std::floor(std::max({xy[v[0]].x, xy[v[1]].x, xy[v[2]].x}))));
    const int y0 = std::max(0, static_cast<int>(std::ceil(std::min({xy[v[0]].y, xy[v[1]].y, xy[v[2]].y}))));
    const int y1 = std::min(H - 1, static_cast<int>(std::floor(std::max({xy[v[0]].y, xy[v[1]].y, xy[v[2]].y}))));
    // A closed opaque solid: a sample on a shared edge may be drawn twice (the z-test keeps one),
    // but must never be missed, so the edge test is inclusive.
    for (int py = y0; py <= y1; ++py) {
      float* zrow = layer.depth.ptr<float>(py);
      float* lrow = layer.level.ptr<float>(py);
      for (int px = x0; px <= x1; ++px) {
        double b[3] = {edge(1, 2, px, py) / area, edge(2, 0, px, py) / area, edge(0, 1, px, py) / area};
        if (b[0] < -1e-12 || b[1] < -1e-12 || b[2] < -1e-12) continue;
        const double iz = b[0] / depth[v[0]] + b[1] / depth[v[1]] + b[2] / depth[v[2]];
        const auto z = static_cast<float>(1 / iz);
        if (z >= zrow[px]) continue;
        zrow[px] = z;
        lrow[px] = static_cast<float>(b[0] * level[v[0]] + b[1] * level[v[1]] + b[2] * level[v[2]]);
      }
    }
  }
  return layer;
}

}  // namespace finverse::vision
