// Lagrangian markers on a zero-thickness immersed surface (see sheet_markers.hpp).
#include "cfd/immersed/sheet_markers.hpp"

#include <algorithm>
#include <cmath>
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
  // Greedy thinning, nodes first, then edge points, then interior points, each in element order
  // (deterministic), on a hash grid of cell `spacing`.
  std::stable_sort(cand.begin(), cand.end(), [](const Candidate& p, const Candidate& q) { return p.rank < q.rank; });
  std::unordered_map<long long, std::vector<Vec3>> kept;
  const auto key = [&](long long i, long long j, long long k) {
    return (i * 73856093LL) ^ (j * 19349663LL) ^ (k * 83492791LL);
  };
  const double dmin2 = spacing * spacing * (1 - 1e-9);
  for (const Candidate& p : cand) {
    const long long ci = static_cast<long long>(std::floor(p.x[0] / spacing)),
                    cj = static_cast<long long>(std::floor(p.x[1] / spacing)),
                    ck = static_cast<long long>(std::floor(p.x[2] / spacing));
    bool near = false;
    for (long long di = -1; di <= 1 && !near; ++di)
      for (long long dj = -1; dj <= 1 && !near; ++dj)
        for (long long dk = -1; dk <= 1 && !near; ++dk) {
          const auto it = kept.find(key(ci + di, cj + dj, ck + dk));
          if (it == kept.end()) continue;
          for (const Vec3& y : it->second)
            if (dot(sub(p.x, y), sub(p.x, y)) < dmin2) {
              near = true;
              break;
            }
        }
    if (near) continue;
    kept[key(ci, cj, ck)].push_back(p.x);
    element_.push_back(p.element);
    node_.push_back(t.elements[static_cast<std::size_t>(p.element)]);
    if (nq == 2) node_.back()[2] = node_.back()[0];
    bary_.push_back(p.bary);
  }
}

std::vector<Vec3> SheetMarkers::at_markers(const std::vector<Vec3>& v) const {
  if (v.size() != topo_.nodes)
    throw Error("sheet markers: " + std::to_string(v.size()) + " node values for " + std::to_string(topo_.nodes) +
                " nodes");
  std::vector<Vec3> out(size(), Vec3{0, 0, 0});
  const int nq = topo_.dim;
  for (std::size_t m = 0; m < size(); ++m)
    for (int q = 0; q < nq; ++q)
      for (int d = 0; d < 3; ++d) out[m][d] += bary_[m][q] * v[node_[m][q]][d];
  return out;
}

std::vector<Vec3> SheetMarkers::to_nodes(const std::vector<Vec3>& f) const {
  std::vector<Vec3> out(topo_.nodes, Vec3{0, 0, 0});
  const int nq = topo_.dim;
  for (std::size_t m = 0; m < size(); ++m)
    for (int q = 0; q < nq; ++q)
      for (int d = 0; d < 3; ++d) out[node_[m][q]][d] += bary_[m][q] * f[m][d];
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
