// Barycentric binding of mesh nodes to a source surface and the motion transfer it defines
// (DESIGN.md section 1, fin-mesh; the closest-point routine is Ericson, Real-Time Collision
// Detection, section 5.1.5).
#include "mesh/motion_transfer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.hpp"

namespace finverse::mesh {
namespace {

using V3 = std::array<double, 3>;
V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Barycentric weights of the point of triangle (a, b, c) closest to p.
std::array<double, 3> closest_barycentric(const V3& p, const V3& a, const V3& b, const V3& c) {
  const V3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const V3 bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const V3 cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {1 - v - w, v, w};
}

}  // namespace

SurfaceBinding bind_to_surface(const NdArray<double>& sp, const NdArray<std::int32_t>& st, const NdArray<double>& targets) {
  if (sp.rank() != 2 || sp.dim(1) != 3 || st.rank() != 2 || st.dim(1) != 3 || st.dim(0) == 0)
    throw Error("motion source: expected a non-empty triangle surface [nv,3] + [ntri,3]");
  const std::size_t nv = sp.dim(0), ntri = st.dim(0), n = targets.dim(0);
  for (auto v : st.data)
    if (v < 0 || static_cast<std::size_t>(v) >= nv)
      throw Error("motion source: triangle vertex " + std::to_string(v) + " out of range [0," + std::to_string(nv) + ")");
  auto vtx = [&](int i) { return V3{sp(i, 0), sp(i, 1), sp(i, 2)}; };
  // Bounding boxes let most triangles be skipped with a cheap test.
  std::vector<std::array<double, 6>> box(ntri);
  for (std::size_t t = 0; t < ntri; ++t) {
    auto& bx = box[t];
    bx = {1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d) {
        bx[d] = std::min(bx[d], sp(st(t, k), d));
        bx[3 + d] = std::max(bx[3 + d], sp(st(t, k), d));
      }
  }
  SurfaceBinding b;
  b.vertices.resize(n);
  b.weights.resize(n);
  std::vector<double> dist(n);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(n); ++i) {
    const V3 p{targets(i, 0), targets(i, 1), targets(i, 2)};
    double best = std::numeric_limits<double>::infinity();
    std::size_t best_t = 0;
    std::array<double, 3> best_w{1, 0, 0};
    for (std::size_t t = 0; t < ntri; ++t) {
      double box_d2 = 0;
      for (int d = 0; d < 3; ++d) {
        const double e = std::max({box[t][d] - p[d], 0.0, p[d] - box[t][3 + d]});
        box_d2 += e * e;
      }
      if (box_d2 >= best) continue;
      const V3 a = vtx(st(t, 0)), bb = vtx(st(t, 1)), c = vtx(st(t, 2));
      const auto w = closest_barycentric(p, a, bb, c);
      V3 q;
      for (int d = 0; d < 3; ++d) q[d] = w[0] * a[d] + w[1] * bb[d] + w[2] * c[d];
      const V3 e = sub(p, q);
      const double d2 = dot(e, e);
      if (d2 < best) {
        best = d2;
        best_t = t;
        best_w = w;
      }
    }
    b.vertices[i] = {st(best_t, 0), st(best_t, 1), st(best_t, 2)};
    b.weights[i] = best_w;
    dist[i] = std::sqrt(best);
  }
  for (double d : dist) b.max_distance = std::max(b.max_distance, d);
  return b;
}

NdArray<double> carry_motion(const SurfaceBinding& b, const NdArray<double>& f) {
  if (f.rank() != 3 || f.dim(2) != 3) throw Error("motion source: expected points [nf,nv,3]");
  const std::size_t nf = f.dim(0), nv = f.dim(1), n = b.vertices.size();
  for (const auto& v : b.vertices)
    for (int k : v)
      if (static_cast<std::size_t>(k) >= nv) throw Error("motion source: points have fewer vertices than the template");
  NdArray<double> out({nf, n, 3});
  for (std::size_t t = 0; t < nf; ++t)
    for (std::size_t i = 0; i < n; ++i)
      for (int d = 0; d < 3; ++d) {
        double x = 0;
        for (int k = 0; k < 3; ++k) x += b.weights[i][k] * f(t, b.vertices[i][k], d);
        out(t, i, d) = x;
      }
  return out;
}

NdArray<double> velocities(const std::vector<double>& time, const NdArray<double>& f, std::optional<double> period) {
  const std::size_t nf = f.dim(0), n = f.dim(1);
  NdArray<double> v({nf, n, 3}, 0.0);
  if (nf < 2) return v;
  if (nf < 3) {
    const double dt = time[1] - time[0];
    for (std::size_t i = 0; i < n * 3; ++i) v.data[i] = v.data[n * 3 + i] = (f.data[n * 3 + i] - f.data[i]) / dt;
    return v;
  }
  const double dt = (time.back() - time.front()) / static_cast<double>(nf - 1);
  bool uniform = true;
  for (std::size_t k = 1; k < nf; ++k) uniform = uniform && std::abs(time[k] - time[k - 1] - dt) <= 1e-9 * dt;
  const bool periodic = uniform && period && std::abs(nf * dt - *period) <= 1e-9 * *period;
  auto at = [&](std::size_t k, std::size_t i) { return f.data[k * n * 3 + i]; };
  for (std::size_t k = 0; k < nf; ++k) {
    for (std::size_t i = 0; i < n * 3; ++i) {
      double d;
      if (k > 0 && k + 1 < nf) {
        const double h0 = time[k] - time[k - 1], h1 = time[k + 1] - time[k];
        // Second order on non-uniform samples too.
        d = (h0 * h0 * at(k + 1, i) - h1 * h1 * at(k - 1, i) - (h0 * h0 - h1 * h1) * at(k, i)) / (h0 * h1 * (h0 + h1));
      } else if (periodic) {
        const std::size_t prev = k == 0 ? nf - 1 : k - 1, next = k + 1 == nf ? 0 : k + 1;
        d = (at(next, i) - at(prev, i)) / (2 * dt);
      } else if (k == 0) {
        const double h = time[1] - time[0];
        d = (-3 * at(0, i) + 4 * at(1, i) - at(2, i)) / (2 * h);
      } else {
        const double h = time[nf - 1] - time[nf - 2];
        d = (3 * at(nf - 1, i) - 4 * at(nf - 2, i) + at(nf - 3, i)) / (2 * h);
      }
      v.data[k * n * 3 + i] = d;
    }
  }
  return v;
}

}  // namespace finverse::mesh
