// Area-coverage silhouette residuals with sub-pixel outline edges (issue 5, edge-on views).
#include "vision/coverage_residual.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <span>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "core/error.hpp"

namespace finverse::vision {
namespace {

constexpr int kCell = 4;            // px, bucket size of the edge and triangle grids
constexpr double kReach = 0.7072;   // a straight edge cuts the unit pixel only this close to its centre
constexpr double kProbe = 0.05;     // px outside an edge where "is anything else there" is tested

double cross(cv::Point2d a, cv::Point2d b) { return a.x * b.y - a.y * b.x; }

}  // namespace

std::vector<MeshEdge> mesh_edges(const NdArray<std::int32_t>& tri) {
  std::map<std::pair<int, int>, std::size_t> index;
  std::vector<MeshEdge> out;
  for (std::size_t t = 0; t < tri.dim(0); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = tri(t, k), b = tri(t, (k + 1) % 3);
      const auto key = std::minmax(a, b);
      const auto [it, fresh] = index.try_emplace(key, out.size());
      if (fresh) {
        out.push_back({a, b, static_cast<int>(t), -1});
      } else {
        auto& e = out[it->second];
        if (e.t1 >= 0) throw Error("coverage residual: mesh edge " + std::to_string(a) + "-" + std::to_string(b) + " has more than two triangles");
        e.t1 = static_cast<int>(t);
      }
    }
  return out;
}

double half_plane_coverage(double d, double nx, double ny, double* slope) {
  // n . u for u uniform on [-1/2, 1/2]^2 is the sum of two uniform variables of widths p >= q:
  // a trapezoidal density, 1/p on |s| <= (p - q)/2, falling linearly to 0 at |s| = (p + q)/2.
  double p = std::abs(nx), q = std::abs(ny);
  if (q > p) std::swap(p, q);
  const double lo = 0.5 * (p - q), hi = 0.5 * (p + q);
  const double s = std::abs(d);
  double c, g;
  if (s >= hi) {
    c = 1, g = 0;
  } else if (s <= lo) {
    c = 0.5 + s / p, g = 1 / p;
  } else {
    const double r = hi - s;
    c = 1 - r * r / (2 * p * q), g = r / (p * q);
  }
  *slope = g;
  return d >= 0 ? c : 1 - c;
}

ModelCoverage::ModelCoverage(const ModelView& m, const NdArray<std::int32_t>& tri, const std::vector<MeshEdge>& edges)
    : m_(m), tri_(tri), edges_(edges) {
  nx_ = m.mask.cols / kCell + 1;
  ny_ = m.mask.rows / kCell + 1;
  edge_cells_.resize(static_cast<std::size_t>(nx_) * ny_);
  tri_cells_.resize(edge_cells_.size());
  auto cells = [&](double x0, double x1, double y0, double y1, auto&& f) {
    const int i0 = std::max(0, static_cast<int>(std::floor(x0 / kCell))), i1 = std::min(nx_ - 1, static_cast<int>(std::floor(x1 / kCell)));
    const int j0 = std::max(0, static_cast<int>(std::floor(y0 / kCell))), j1 = std::min(ny_ - 1, static_cast<int>(std::floor(y1 / kCell)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) f(static_cast<std::size_t>(j) * nx_ + i);
  };
  auto third = [&](int t, const MeshEdge& e) {
    for (int k = 0; k < 3; ++k)
      if (tri(t, k) != e.a && tri(t, k) != e.b) return m.uv[static_cast<std::size_t>(tri(t, k))];
    return m.uv[static_cast<std::size_t>(e.a)];
  };
  // Outline candidates: boundary edges, and folds (both triangles on one side of the edge in the
  // image). Whether a candidate is really on the outline where a pixel looks at it (not hidden
  // under another layer of the fin) is decided per query.
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const auto& e = edges[i];
    const cv::Point2d a = m.uv[static_cast<std::size_t>(e.a)], b = m.uv[static_cast<std::size_t>(e.b)];
    const cv::Point2d ab = b - a;
    const double len = std::hypot(ab.x, ab.y);
    if (len < 1e-9) continue;
    const double s0 = cross(ab, third(e.t0, e) - a);
    if (s0 == 0) continue;
    if (e.t1 >= 0) {
      const double s1 = cross(ab, third(e.t1, e) - a);
      if ((s0 > 0) != (s1 > 0) || s1 == 0) continue;  // an interior edge of the projected sheet
    }
    cv::Point2d n(-ab.y / len, ab.x / len);
    if (s0 < 0) n = -n;
    const int id = static_cast<int>(outline_.size());
    outline_.push_back(static_cast<int>(i));
    inward_.push_back(n);
    cells(std::min(a.x, b.x) - kReach, std::max(a.x, b.x) + kReach, std::min(a.y, b.y) - kReach, std::max(a.y, b.y) + kReach,
          [&](std::size_t c) { edge_cells_[c].push_back(id); });
  }
  for (std::size_t t = 0; t < tri.dim(0); ++t) {
    const auto& a = m.uv[static_cast<std::size_t>(tri(t, 0))];
    const auto& b = m.uv[static_cast<std::size_t>(tri(t, 1))];
    const auto& c = m.uv[static_cast<std::size_t>(tri(t, 2))];
    if (cross(b - a, c - a) == 0) continue;
    cells(std::min({a.x, b.x, c.x}), std::max({a.x, b.x, c.x}), std::min({a.y, b.y, c.y}), std::max({a.y, b.y, c.y}),
          [&](std::size_t cc) { tri_cells_[cc].push_back(static_cast<int>(t)); });
  }
}

bool ModelCoverage::covered_by_others(cv::Point2d q, const MeshEdge& e) const {
  const int i = static_cast<int>(std::floor(q.x / kCell)), j = static_cast<int>(std::floor(q.y / kCell));
  if (i < 0 || j < 0 || i >= nx_ || j >= ny_) return false;
  for (int t : tri_cells_[static_cast<std::size_t>(j) * nx_ + i]) {
    if (t == e.t0 || t == e.t1) continue;
    const auto& a = m_.uv[static_cast<std::size_t>(tri_(t, 0))];
    const auto& b = m_.uv[static_cast<std::size_t>(tri_(t, 1))];
    const auto& c = m_.uv[static_cast<std::size_t>(tri_(t, 2))];
    const double s = cross(b - a, c - a) > 0 ? 1.0 : -1.0;
    if (s * cross(b - a, q - a) > 0 && s * cross(c - b, q - b) > 0 && s * cross(a - c, q - c) > 0) return true;
  }
  return false;
}

ModelCoverage::Sample ModelCoverage::at(int x, int y) const {
  Sample out;
  const bool centre_in = m_.mask.at<std::uint8_t>(y, x) != 0;
  out.coverage = centre_in ? 1.0 : 0.0;
  const std::size_t cell = static_cast<std::size_t>(y / kCell) * nx_ + x / kCell;
  const cv::Point2d p(x, y);
  // Nearest outline edge (distance to the segment) that is really on the outline there.
  // The outline edges that reach the pixel, nearest first (a handful; more are never needed).
  constexpr std::size_t kMax = 12;
  std::array<std::pair<double, int>, kMax> buf;
  std::size_t count = 0;
  for (int id : edge_cells_[cell]) {
    const auto& e = edges_[static_cast<std::size_t>(outline_[static_cast<std::size_t>(id)])];
    const cv::Point2d a = m_.uv[static_cast<std::size_t>(e.a)], ab = m_.uv[static_cast<std::size_t>(e.b)] - a;
    const double t = std::clamp((p - a).dot(ab) / ab.dot(ab), 0.0, 1.0);
    const cv::Point2d f = a + t * ab;
    const double dist = std::hypot(p.x - f.x, p.y - f.y);
    if (dist >= kReach) continue;
    if (count < kMax) {
      buf[count++] = {dist, id};
    } else if (buf[kMax - 1].first > dist || (buf[kMax - 1].first == dist && buf[kMax - 1].second > id)) {
      buf[kMax - 1] = {dist, id};
    } else {
      continue;
    }
    std::sort(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(count));
  }
  const std::span<const std::pair<double, int>> near(buf.data(), count);
  std::array<double, 2> c{0, 0};
  std::array<cv::Point2d, 2> foot;
  for (const auto& [dist, id] : near) {
    const int ei = outline_[static_cast<std::size_t>(id)];
    const auto& e = edges_[static_cast<std::size_t>(ei)];
    const cv::Point2d a = m_.uv[static_cast<std::size_t>(e.a)], ab = m_.uv[static_cast<std::size_t>(e.b)] - a;
    const cv::Point2d n = inward_[static_cast<std::size_t>(id)];
    // The second edge must face the first one's opposite way (else it continues the same outline).
    if (out.count == 1 && n.dot(out.n[0]) > -0.5) continue;
    const double t = (p - a).dot(ab) / ab.dot(ab);
    const double d = n.dot(p - a);
    // The pixel centre must be on the side of the edge the rasterised silhouette puts it (else
    // another layer covers it), and just outside the edge there must be nothing else of the fin.
    if ((centre_in && d < -0.05) || (!centre_in && d > 0.05)) continue;
    const cv::Point2d probe = a + std::clamp(t, 0.05, 0.95) * ab - kProbe * n;
    if (covered_by_others(probe, e)) continue;
    const int k = out.count++;
    c[k] = half_plane_coverage(d, n.x, n.y, &out.slope[k]);
    out.edge[k] = ei;
    out.t[k] = t;
    out.n[k] = n;
    foot[k] = a + std::clamp(t, 0.0, 1.0) * ab;
    if (out.count == 2) break;
  }
  if (out.count == 1) out.coverage = c[0];
  if (out.count == 2) {
    // Sliver: each edge's inner side faces the other edge; gap: each faces away.
    const bool sliver = out.n[0].dot(foot[1] - foot[0]) > 0;
    const double v = sliver ? c[0] + c[1] - 1 : c[0] + c[1];
    out.coverage = std::clamp(v, 0.0, 1.0);
    if (v != out.coverage) out.slope = {0, 0};
  }
  return out;
}

cv::Mat ModelCoverage::image() const {
  cv::Mat out(m_.mask.size(), CV_32F);
  for (int y = 0; y < out.rows; ++y)
    for (int x = 0; x < out.cols; ++x) out.at<float>(y, x) = static_cast<float>(at(x, y).coverage);
  return out;
}

CoverageStats add_coverage_residuals(const ViewData& view, const ModelView& m, const NdArray<std::int32_t>& tri,
                                     const std::vector<MeshEdge>& edges, const SkinJacobian* J, const CoverageOptions& o,
                                     NormalEquations& ne) {
  CoverageStats st;
  if (!view.valid || view.coverage.empty()) return st;
  const ModelCoverage cover(m, tri, edges);
  // The band is the data's (it does not move with the model, so costs of LM candidates compare).
  cv::Rect roi = cv::boundingRect(view.mask);
  const int pad = static_cast<int>(std::ceil(o.band_px)) + 1;
  roi = cv::Rect(roi.x - pad, roi.y - pad, roi.width + 2 * pad, roi.height + 2 * pad) & cv::Rect(0, 0, view.mask.cols, view.mask.rows);
  double sum2 = 0;
  for (int y = roi.y; y < roi.y + roi.height; ++y) {
    const auto* sd = view.sdf.ptr<float>(y);
    const auto* cd = view.coverage.ptr<float>(y);
    const auto* body = view.body.empty() ? nullptr : view.body.ptr<std::uint8_t>(y);
    for (int x = roi.x; x < roi.x + roi.width; ++x) {
      if (std::abs(sd[x]) > o.band_px || (body && body[x])) continue;  // off the band, or the opaque body's
      const auto s = cover.at(x, y);
      const double r = s.coverage - cd[x];
      const double w = o.weight * (std::abs(r) <= o.huber ? 1.0 : o.huber / std::abs(r));
      sum2 += r * r;
      ++st.residuals;
      if (!J || s.count == 0 || (s.slope[0] == 0 && s.slope[1] == 0)) {
        ne.cost_only(r, w);
        continue;
      }
      for (int j = 0; j < s.count; ++j) {
        const auto& e = edges[static_cast<std::size_t>(s.edge[j])];
        // d(coverage)/d(uv) of the edge's vertices: slope * dd/da = -slope (1 - t) n, dd/db = -slope t n.
        const std::array<std::pair<int, double>, 2> ends{{{e.a, -s.slope[j] * (1 - s.t[j])}, {e.b, -s.slope[j] * s.t[j]}}};
        for (const auto& [v, k] : ends) {
          const cv::Matx23d& P = m.duv_dX[static_cast<std::size_t>(v)];
          const double gx = k * s.n[j].x, gy = k * s.n[j].y;
          const cv::Vec3d gP(gx * P(0, 0) + gy * P(1, 0), gx * P(0, 1) + gy * P(1, 1), gx * P(0, 2) + gy * P(1, 2));
          const auto& cols = J->cols[static_cast<std::size_t>(v)];
          const auto& vals = J->vals[static_cast<std::size_t>(v)];
          for (std::size_t c = 0; c < cols.size(); ++c) ne.add(cols[c], gP.dot(vals[c]));
        }
      }
      ne.commit(r, w);
    }
  }
  st.rms = st.residuals ? std::sqrt(sum2 / st.residuals) : 0.0;
  return st;
}

}  // namespace finverse::vision
