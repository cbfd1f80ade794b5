// Lagrangian markers on a zero-thickness immersed surface (see sheet_markers.hpp).
#include "cfd/immersed/sheet_markers.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_map>

#include "core/error.hpp"

namespace finverse::cfd {
namespace {

Vec3 add3(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }

// Seeds on a hash grid of cell `spacing`. On a periodic axis (period > 0) positions are kept in
// [origin, origin + period) and searched at their images too, so that distances are the
// minimum-image ones; on the other axes positions stay as they are.
class SeedIndex {
 public:
  SeedIndex(double spacing, const std::array<double, 3>& period, const Vec3& origin)
      : h_(spacing), period_(period), origin_(origin) {}
  Vec3 wrap(const Vec3& x) const {
    Vec3 w = x;
    for (int d = 0; d < 3; ++d)
      if (period_[d] > 0) {
        const double P = period_[d];
        w[d] = origin_[d] + std::fmod(std::fmod(x[d] - origin_[d], P) + P, P);
        if (w[d] >= origin_[d] + P) w[d] -= P;  // fmod's round-off at the top
      }
    return w;
  }
  void add(const Vec3& x) {
    const auto c = cell(x);
    grid_[key(c[0], c[1], c[2])].push_back(static_cast<int>(seed_.size()));
    seed_.push_back(x);
  }
  std::size_t size() const { return seed_.size(); }
  const Vec3& seed(int q) const { return seed_[static_cast<std::size_t>(q)]; }
  // fn(q, image) for every seed q in the (2 r + 1)^3 hash cells around each image x + image of x.
  template <class Fn>
  void near(const Vec3& x, int r, Fn&& fn) const {
    const int ix = period_[0] > 0 ? 1 : 0, iy = period_[1] > 0 ? 1 : 0, iz = period_[2] > 0 ? 1 : 0;
    for (int a = -ix; a <= ix; ++a)
      for (int b = -iy; b <= iy; ++b)
        for (int g = -iz; g <= iz; ++g) {
          const Vec3 image{a * period_[0], b * period_[1], g * period_[2]};
          const auto c = cell(add3(x, image));
          for (long long di = -r; di <= r; ++di)
            for (long long dj = -r; dj <= r; ++dj)
              for (long long dk = -r; dk <= r; ++dk) {
                const auto it = grid_.find(key(c[0] + di, c[1] + dj, c[2] + dk));
                if (it == grid_.end()) continue;
                for (int q : it->second) fn(q, image);
              }
        }
  }

 private:
  std::array<long long, 3> cell(const Vec3& x) const {
    return {static_cast<long long>(std::floor(x[0] / h_)), static_cast<long long>(std::floor(x[1] / h_)),
            static_cast<long long>(std::floor(x[2] / h_))};
  }
  static long long key(long long i, long long j, long long k) {
    return (i * 73856093LL) ^ (j * 19349663LL) ^ (k * 83492791LL);
  }
  double h_;
  std::array<double, 3> period_;
  Vec3 origin_;
  std::unordered_map<long long, std::vector<int>> grid_;  // hash cell -> seeds
  std::vector<Vec3> seed_;
};

double element_measure(int dim, const Vec3& a, const Vec3& b, const Vec3& c) {
  if (dim == 2) return norm(sub(b, a));
  return 0.5 * norm(cross(sub(b, a), sub(c, a)));
}

}  // namespace

SheetMarkers::SheetMarkers(const SheetTopology& t, const std::vector<Vec3>& rest, double spacing,
                           const std::string& what, const std::array<double, 3>& period)
    : topo_(t), spacing_(spacing) {
  if (t.dim != 2 && t.dim != 3) throw Error(what + ": sheet dimension " + std::to_string(t.dim) + ", expected 2 or 3");
  if (rest.size() != t.nodes)
    throw Error(what + ": " + std::to_string(rest.size()) + " rest positions for " + std::to_string(t.nodes) +
                " nodes");
  if (!(spacing > 0) || !std::isfinite(spacing))
    throw Error(what + ": marker spacing " + std::to_string(spacing) + ", expected a positive finite length");
  if (t.elements.empty()) throw Error(what + ": the sheet has no elements");
  for (int d = 0; d < 3; ++d)
    if (!(period[d] == 0 || (std::isfinite(period[d]) && period[d] >= 4 * spacing)))
      throw Error(what + ": period " + std::to_string(period[d]) + " along axis " + std::to_string(d) +
                  ", expected 0 (not periodic) or at least 4 marker spacings");
  // The sheet's extent, the scale of the degeneracy test.
  Vec3 lo = rest.front(), hi = rest.front();
  for (const Vec3& p : rest)
    for (int d = 0; d < 3; ++d) {
      if (!std::isfinite(p[d])) throw Error(what + ": a rest position is not finite");
      lo[d] = std::min(lo[d], p[d]);
      hi[d] = std::max(hi[d], p[d]);
    }
  const double extent = norm(sub(hi, lo));
  const int nq = t.dim;  // nodes per element
  struct Candidate {
    int element, rank;  // rank 0: a node, 1: on an edge, 2: inside
    std::array<double, 3> bary;
    Vec3 x;
  };
  std::vector<Candidate> cand;
  for (std::size_t e = 0; e < t.elements.size(); ++e) {
    const auto& el = t.elements[e];
    for (int q = 0; q < nq; ++q)
      if (el[q] < 0 || static_cast<std::size_t>(el[q]) >= t.nodes)
        throw Error(what + ": element " + std::to_string(e) + " refers to node " + std::to_string(el[q]) + " of " +
                    std::to_string(t.nodes));
    const Vec3& a = rest[el[0]];
    const Vec3& b = rest[el[1]];
    const Vec3& c = nq == 3 ? rest[el[2]] : a;
    const double m = element_measure(t.dim, a, b, c);
    const double scale = t.dim == 2 ? extent : extent * extent;
    if (!(m > 1e-12 * scale))
      throw Error(what + ": element " + std::to_string(e) + " is degenerate (" + (t.dim == 2 ? "length " : "area ") +
                  std::to_string(m) + ")");
    const double longest = nq == 2 ? m : std::max({norm(sub(b, a)), norm(sub(c, b)), norm(sub(a, c))});
    const int n = std::max(1, static_cast<int>(std::ceil(longest / (0.5 * spacing) - 1e-9)));
    const auto add = [&](std::array<double, 3> w, int zeros) {
      Vec3 x{0, 0, 0};
      for (int d = 0; d < 3; ++d) x[d] = w[0] * a[d] + w[1] * b[d] + (nq == 3 ? w[2] * c[d] : 0.0);
      cand.push_back({static_cast<int>(e), nq - 1 - zeros == 0 ? 0 : zeros > 0 ? 1 : 2, w, x});
    };
    if (nq == 2) {
      for (int i = 0; i <= n; ++i) add({1.0 - double(i) / n, double(i) / n, 0.0}, (i == 0 || i == n) ? 1 : 0);
      continue;
    }
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const int k = n - i - j;
        add({double(k) / n, double(i) / n, double(j) / n}, (i == 0) + (j == 0) + (k == 0));
      }
  }
  // Greedy thinning of the subdivision's vertices into seeds, nodes first, then edge points, then
  // interior points, each in element order (deterministic).
  std::stable_sort(cand.begin(), cand.end(), [](const Candidate& p, const Candidate& q) { return p.rank < q.rank; });
  SeedIndex index(spacing, period, lo);
  const double dmin2 = spacing * spacing * (1 - 1e-9);
  for (const Candidate& p : cand) {
    const Vec3 x = index.wrap(p.x);
    bool near = false;
    index.near(x, 1, [&](int q, const Vec3& image) {
      const Vec3 d = sub(add3(x, image), index.seed(q));
      near = near || dot(d, d) < dmin2;
    });
    if (near) continue;
    index.add(x);
    element_.push_back(p.element);
  }
  // Patches: every piece's centroid (n^2 per triangle, n per segment, the same n as the
  // candidates) goes to its nearest seed (ties: the lower seed), with its area and barycentric
  // weights. Every candidate lies within `spacing` of a seed, so the nearest seed of a centroid is
  // within two spacings: a 5 x 5 x 5 block of hash cells holds it. (Pieces shared smoothly among
  // the seeds within 1.5 spacings instead smeared the sheet's edges and made the towed plate's
  // force oscillation larger, 4.2 % against 3.2 % at c/32: docs/studies/thin_surface.md.) On a
  // periodic axis a piece may lie a period away from its seed: its shift is kept in the marker's
  // offset, so that the marker's position is the patch's mean beside the seed.
  const std::size_t ns = index.size();
  std::vector<std::map<int, double>> patch(ns);
  std::vector<double> patch_area(ns, 0.0);
  std::vector<Vec3> shift_sum(ns, Vec3{0, 0, 0});
  for (std::size_t e = 0; e < t.elements.size(); ++e) {
    const auto& el = t.elements[e];
    const Vec3& a = rest[el[0]];
    const Vec3& b = rest[el[1]];
    const Vec3& c = nq == 3 ? rest[el[2]] : a;
    const double m = element_measure(t.dim, a, b, c);
    const double longest = nq == 2 ? m : std::max({norm(sub(b, a)), norm(sub(c, b)), norm(sub(a, c))});
    const int n = std::max(1, static_cast<int>(std::ceil(longest / (0.5 * spacing) - 1e-9)));
    std::vector<std::array<double, 3>> pieces;  // barycentric centroids, equal areas
    if (nq == 2) {
      for (int i = 0; i < n; ++i) pieces.push_back({1 - (i + 0.5) / n, (i + 0.5) / n, 0.0});
    } else {
      for (int i = 0; i < n; ++i)
        for (int j = 0; i + j < n; ++j) {
          pieces.push_back({1 - (i + j + 2.0 / 3) / n, (i + 1.0 / 3) / n, (j + 1.0 / 3) / n});
          if (i + j + 1 < n) pieces.push_back({1 - (i + j + 4.0 / 3) / n, (i + 2.0 / 3) / n, (j + 2.0 / 3) / n});
        }
    }
    const double area = m / static_cast<double>(pieces.size());
    for (const auto& w : pieces) {
      Vec3 x{0, 0, 0};
      for (int d = 0; d < 3; ++d) x[d] = w[0] * a[d] + w[1] * b[d] + (nq == 3 ? w[2] * c[d] : 0.0);
      const Vec3 xw = index.wrap(x);
      int best = -1;
      double best_d2 = std::numeric_limits<double>::infinity();
      Vec3 best_image{0, 0, 0};
      index.near(xw, 2, [&](int q, const Vec3& image) {
        const Vec3 d = sub(add3(xw, image), index.seed(q));
        const double d2 = dot(d, d);
        if (d2 < best_d2 || (d2 == best_d2 && q < best)) best = q, best_d2 = d2, best_image = image;
      });
      if (best < 0) throw Error(what + ": element " + std::to_string(e) + " has no marker within two spacings");
      const auto B = static_cast<std::size_t>(best);
      patch_area[B] += area;
      for (int k = 0; k < nq; ++k) patch[B][el[k]] += area * w[k];
      const Vec3 shift = add3(sub(xw, x), best_image);
      for (int d = 0; d < 3; ++d) shift_sum[B][d] += area * shift[d];
    }
  }
  start_.push_back(0);
  offset_.assign(ns, Vec3{0, 0, 0});
  for (std::size_t k = 0; k < ns; ++k) {
    if (!(patch_area[k] > 0)) throw Error(what + ": a marker has no piece of the sheet (degenerate sampling)");
    for (int d = 0; d < 3; ++d) offset_[k][d] = shift_sum[k][d] / patch_area[k];
    for (const auto& [node, w] : patch[k]) {
      node_.push_back(node);
      weight_.push_back(w / patch_area[k]);
    }
    start_.push_back(node_.size());
  }
}

std::vector<Vec3> SheetMarkers::at_markers(const std::vector<Vec3>& v) const {
  if (v.size() != topo_.nodes)
    throw Error("sheet markers: " + std::to_string(v.size()) + " node values for " + std::to_string(topo_.nodes) +
                " nodes");
  std::vector<Vec3> out(size(), Vec3{0, 0, 0});
  for (std::size_t m = 0; m < size(); ++m)
    for (std::size_t e = start_[m]; e < start_[m + 1]; ++e)
      for (int d = 0; d < 3; ++d) out[m][d] += weight_[e] * v[static_cast<std::size_t>(node_[e])][d];
  return out;
}

std::vector<Vec3> SheetMarkers::positions_at_markers(const std::vector<Vec3>& x) const {
  std::vector<Vec3> out = at_markers(x);
  for (std::size_t m = 0; m < size(); ++m) out[m] = add3(out[m], offset_[m]);
  return out;
}

std::vector<Vec3> SheetMarkers::to_nodes(const std::vector<Vec3>& f) const {
  std::vector<Vec3> out(topo_.nodes, Vec3{0, 0, 0});
  for (std::size_t m = 0; m < size(); ++m)
    for (std::size_t e = start_[m]; e < start_[m + 1]; ++e)
      for (int d = 0; d < 3; ++d) out[static_cast<std::size_t>(node_[e])][d] += weight_[e] * f[m][d];
  return out;
}

void SheetMarkers::element_geometry(const std::vector<Vec3>& x, std::vector<double>& measure,
                                    std::vector<Vec3>& normal) const {
  const std::size_t ne = topo_.elements.size();
  measure.assign(ne, 0.0);
  normal.assign(ne, Vec3{0, 0, 0});
  for (std::size_t e = 0; e < ne; ++e) {
    const auto& el = topo_.elements[e];
    const Vec3& a = x[el[0]];
    const Vec3& b = x[el[1]];
    if (topo_.dim == 2) {
      const Vec3 t = sub(b, a);
      const double l = std::hypot(t[0], t[1]);
      measure[e] = l;
      if (l > 0) normal[e] = {-t[1] / l, t[0] / l, 0};
      continue;
    }
    const Vec3 n = cross(sub(b, a), sub(x[el[2]], a));
    const double l = norm(n);
    measure[e] = 0.5 * l;
    if (l > 0) normal[e] = {n[0] / l, n[1] / l, n[2] / l};
  }
}

std::vector<double> SheetMarkers::node_measure(const std::vector<Vec3>& x) const {
  std::vector<double> me;
  std::vector<Vec3> n;
  element_geometry(x, me, n);
  std::vector<double> out(topo_.nodes, 0.0);
  for (std::size_t e = 0; e < me.size(); ++e)
    for (int q = 0; q < topo_.dim; ++q) out[static_cast<std::size_t>(topo_.elements[e][q])] += me[e] / topo_.dim;
  return out;
}

}  // namespace finverse::cfd
