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

double element_measure(int dim, const Vec3& a, const Vec3& b, const Vec3& c) {
  if (dim == 2) return norm(sub(b, a));
  return 0.5 * norm(cross(sub(b, a), sub(c, a)));
}

}  // namespace

SheetMarkers::SheetMarkers(const SheetTopology& t, const std::vector<Vec3>& rest, double spacing,
                           const std::string& what)
    : topo_(t), spacing_(spacing) {
  if (t.dim != 2 && t.dim != 3) throw Error(what + ": sheet dimension " + std::to_string(t.dim) + ", expected 2 or 3");
  if (rest.size() != t.nodes)
    throw Error(what + ": " + std::to_string(rest.size()) + " rest positions for " + std::to_string(t.nodes) +
                " nodes");
  if (!(spacing > 0) || !std::isfinite(spacing))
    throw Error(what + ": marker spacing " + std::to_string(spacing) + ", expected a positive finite length");
  if (t.elements.empty()) throw Error(what + ": the sheet has no elements");
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
  // interior points, each in element order (deterministic), on a hash grid of cell `spacing`.
  std::stable_sort(cand.begin(), cand.end(), [](const Candidate& p, const Candidate& q) { return p.rank < q.rank; });
  const auto cell_of = [&](const Vec3& x) {
    return std::array<long long, 3>{static_cast<long long>(std::floor(x[0] / spacing)),
                                    static_cast<long long>(std::floor(x[1] / spacing)),
                                    static_cast<long long>(std::floor(x[2] / spacing))};
  };
  const auto key = [](long long i, long long j, long long k) {
    return (i * 73856093LL) ^ (j * 19349663LL) ^ (k * 83492791LL);
  };
  std::unordered_map<long long, std::vector<int>> grid;  // hash cell -> seeds
  std::vector<Vec3> seed;
  const double dmin2 = spacing * spacing * (1 - 1e-9);
  for (const Candidate& p : cand) {
    const auto c = cell_of(p.x);
    bool near = false;
    for (long long di = -1; di <= 1 && !near; ++di)
      for (long long dj = -1; dj <= 1 && !near; ++dj)
        for (long long dk = -1; dk <= 1 && !near; ++dk) {
          const auto it = grid.find(key(c[0] + di, c[1] + dj, c[2] + dk));
          if (it == grid.end()) continue;
          for (int q : it->second)
            if (dot(sub(p.x, seed[static_cast<std::size_t>(q)]), sub(p.x, seed[static_cast<std::size_t>(q)])) < dmin2) {
              near = true;
              break;
            }
        }
    if (near) continue;
    grid[key(c[0], c[1], c[2])].push_back(static_cast<int>(seed.size()));
    seed.push_back(p.x);
    element_.push_back(p.element);
  }
  // Patches: every piece's centroid (n^2 per triangle, n per segment, the same n as the
  // candidates) goes to its nearest seed (ties: the lower seed), with its area and barycentric
  // weights. Every candidate lies within `spacing` of a seed, so the nearest seed of a centroid is
  // within two spacings: a 5 x 5 x 5 block of hash cells holds it. (Pieces shared smoothly among
  // the seeds within 1.5 spacings instead smeared the sheet's edges and made the towed plate's
  // force oscillation larger, 4.2 % against 3.2 % at c/32: docs/studies/thin_surface.md.)
  std::vector<std::map<int, double>> patch(seed.size());
  std::vector<double> patch_area(seed.size(), 0.0);
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
      const auto cc = cell_of(x);
      int best = -1;
      double best_d2 = std::numeric_limits<double>::infinity();
      for (long long di = -2; di <= 2; ++di)
        for (long long dj = -2; dj <= 2; ++dj)
          for (long long dk = -2; dk <= 2; ++dk) {
            const auto it = grid.find(key(cc[0] + di, cc[1] + dj, cc[2] + dk));
            if (it == grid.end()) continue;
            for (int q : it->second) {
              const double d2 =
                  dot(sub(x, seed[static_cast<std::size_t>(q)]), sub(x, seed[static_cast<std::size_t>(q)]));
              if (d2 < best_d2 || (d2 == best_d2 && q < best)) best = q, best_d2 = d2;
            }
          }
      if (best < 0) throw Error(what + ": element " + std::to_string(e) + " has no marker within two spacings");
      const auto B = static_cast<std::size_t>(best);
      patch_area[B] += area;
      for (int k = 0; k < nq; ++k) patch[B][el[k]] += area * w[k];
    }
  }
  start_.push_back(0);
  for (std::size_t k = 0; k < seed.size(); ++k) {
    if (!(patch_area[k] > 0)) throw Error(what + ": a marker has no piece of the sheet (degenerate sampling)");
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
