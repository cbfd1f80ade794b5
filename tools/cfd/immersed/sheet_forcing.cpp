// Regularized interpolation and spreading for the zero-thickness immersed surface, and the
// marker system M g = b (see sheet_forcing.hpp). Every loop runs in marker order on one thread:
// the sheet has 1e2-1e4 markers against 1e5-1e7 cells, and a fixed order makes each step
// bitwise reproducible for any thread count.
#include "cfd/immersed/sheet_forcing.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace finverse::cfd {
namespace {

struct AxisWeights {
  std::vector<int> index;
  std::vector<double> weight;
};

// The 1-D weights of coordinate x on axis `ax` (the kernel around the cell that holds x).
AxisWeights axis_weights(const Axis& ax, bool periodic, double x, DeltaKernel kernel, int d, const std::string& what) {
  static const char* names = "xyz";
  const auto& f = ax.faces();
  const int n = ax.size();
  const double L = ax.length();
  double xw = x;
  if (periodic) xw = ax.lo() + std::fmod(std::fmod(x - ax.lo(), L) + L, L);
  if (!(xw >= ax.lo() && xw <= ax.hi()))
    throw Error(what + ": a marker at " + names[d] + " = " + std::to_string(x) + " is outside the domain [" +
                std::to_string(ax.lo()) + ", " + std::to_string(ax.hi()) + "]");
  const int ic = std::clamp(static_cast<int>(std::upper_bound(f.begin(), f.end(), xw) - f.begin()) - 1, 0, n - 1);
  const double h = ax.width(ic);
  const double support = delta_kernel_half_support(kernel);
  const int reach = static_cast<int>(std::ceil(support)) + 1;
  AxisWeights w;
  double sum = 0;
  for (int i = ic - reach; i <= ic + reach; ++i) {
    int iw = i;
    double shift = 0;
    if (i < 0 || i >= n) {
      if (!periodic) {
        // A cell beyond the boundary that the kernel would reach: the sheet is too close to it.
        const double centre = i < 0 ? ax.lo() - (-i - 0.5) * ax.width(0) : ax.hi() + (i - n + 0.5) * ax.width(n - 1);
        if (delta_kernel(kernel, (xw - centre) / h) > 0)
          throw Error(what + ": the sheet comes within " + std::to_string(support) + " cells of the domain's " +
                      names[d] + " boundary (a marker at " + names[d] + " = " + std::to_string(x) + ")");
        continue;
      }
      iw = ((i % n) + n) % n;
      shift = i < 0 ? -L : L;
    }
    const double phi = delta_kernel(kernel, (xw - (ax.centre(iw) + shift)) / h);
    if (phi <= 0) continue;
    w.index.push_back(iw);
    w.weight.push_back(phi);
    sum += phi;
  }
  for (double& v : w.weight) v /= sum;
  return w;
}

}  // namespace

RegularizedStencils::RegularizedStencils(const StretchedGrid& grid, const std::array<bool, 3>& periodic,
                                         const std::vector<Vec3>& markers, DeltaKernel kernel,
                                         const std::string& what) {
  const int D = grid.dim();
  start_.reserve(markers.size() + 1);
  start_.push_back(0);
  std::vector<long> linear;  // entry -> linear cell index, before compaction
  const long nx = grid.nx(), ny = grid.ny();
  for (const Vec3& X : markers) {
    for (int d = 0; d < D; ++d)
      if (!std::isfinite(X[d])) throw Error(what + ": a marker position is not finite");
    std::array<AxisWeights, 3> w;
    for (int d = 0; d < D; ++d) w[d] = axis_weights(grid.axis(d), periodic[d], X[d], kernel, d, what);
    if (D == 2) w[2] = {{0}, {1.0}};
    for (std::size_t c = 0; c < w[2].index.size(); ++c)
      for (std::size_t b = 0; b < w[1].index.size(); ++b)
        for (std::size_t a = 0; a < w[0].index.size(); ++a) {
          const double wt = w[0].weight[a] * w[1].weight[b] * w[2].weight[c];
          if (wt <= 0) continue;
          linear.push_back(w[0].index[a] + nx * (w[1].index[b] + ny * w[2].index[c]));
          weight_.push_back(wt);
        }
    start_.push_back(weight_.size());
  }
  std::vector<long> unique = linear;
  std::sort(unique.begin(), unique.end());
  unique.erase(std::unique(unique.begin(), unique.end()), unique.end());
  cell_.resize(unique.size());
  inv_volume_.resize(unique.size());
  for (std::size_t c = 0; c < unique.size(); ++c) {
    const int i = static_cast<int>(unique[c] % nx), j = static_cast<int>((unique[c] / nx) % ny),
              k = static_cast<int>(unique[c] / (nx * ny));
    cell_[c] = {i, j, k};
    inv_volume_[c] = 1.0 / grid.volume(i, j, k);
  }
  local_.resize(linear.size());
  for (std::size_t e = 0; e < linear.size(); ++e)
    local_[e] = static_cast<int>(std::lower_bound(unique.begin(), unique.end(), linear[e]) - unique.begin());
  work_.assign(cell_.size(), 0.0);
}

void RegularizedStencils::interpolate(const Field& q, std::vector<double>& out) const {
  const std::size_t nm = markers();
  out.assign(nm, 0.0);
  for (std::size_t c = 0; c < cell_.size(); ++c) work_[c] = q(cell_[c][0], cell_[c][1], cell_[c][2]);
  for (std::size_t m = 0; m < nm; ++m) {
    double s = 0;
    for (std::size_t e = start_[m]; e < start_[m + 1]; ++e)
      s += weight_[e] * work_[static_cast<std::size_t>(local_[e])];
    out[m] = s;
  }
}

void RegularizedStencils::spread(const std::vector<double>& g, double scale, Field& q) const {
  std::fill(work_.begin(), work_.end(), 0.0);
  for (std::size_t m = 0; m < markers(); ++m)
    for (std::size_t e = start_[m]; e < start_[m + 1]; ++e)
      work_[static_cast<std::size_t>(local_[e])] += weight_[e] * g[m];
  for (std::size_t c = 0; c < cell_.size(); ++c)
    q(cell_[c][0], cell_[c][1], cell_[c][2]) += scale * work_[c] * inv_volume_[c];
}

void RegularizedStencils::apply(const std::vector<double>& x, std::vector<double>& y) const {
  std::fill(work_.begin(), work_.end(), 0.0);
  const std::size_t nm = markers();
  for (std::size_t m = 0; m < nm; ++m)
    for (std::size_t e = start_[m]; e < start_[m + 1]; ++e)
      work_[static_cast<std::size_t>(local_[e])] += weight_[e] * x[m];
  for (std::size_t c = 0; c < cell_.size(); ++c) work_[c] *= inv_volume_[c];
  y.assign(nm, 0.0);
  for (std::size_t m = 0; m < nm; ++m) {
    double s = 0;
    for (std::size_t e = start_[m]; e < start_[m + 1]; ++e)
      s += weight_[e] * work_[static_cast<std::size_t>(local_[e])];
    y[m] = s;
  }
}

std::vector<double> RegularizedStencils::diagonal() const {
  std::vector<double> d(markers(), 0.0);
  for (std::size_t m = 0; m < markers(); ++m)
    for (std::size_t e = start_[m]; e < start_[m + 1]; ++e)
      d[m] += weight_[e] * weight_[e] * inv_volume_[static_cast<std::size_t>(local_[e])];
  return d;
}

SheetSolveStats solve_marker_system(const RegularizedStencils& s, const std::vector<double>& b, std::vector<double>& g,
                                    const SheetForcingOptions& opt, const std::string& what) {
  const std::size_t n = s.markers();
  g.assign(n, 0.0);
  SheetSolveStats st;
  double bb = 0;
  for (double v : b) bb += v * v;
  if (bb == 0) return st;
  const std::vector<double> diag = s.diagonal();
  std::vector<double> r = b, z(n), p(n), q(n);
  for (std::size_t m = 0; m < n; ++m) z[m] = r[m] / diag[m];
  p = z;
  double rz = 0;
  for (std::size_t m = 0; m < n; ++m) rz += r[m] * z[m];
  const double target = opt.rtol * opt.rtol * bb;
  double rr = bb;
  for (int it = 1; it <= opt.max_iterations; ++it) {
    s.apply(p, q);
    double pq = 0;
    for (std::size_t m = 0; m < n; ++m) pq += p[m] * q[m];
    if (!(pq > 0)) break;  // M is not positive definite on p: markers far too dense
    const double alpha = rz / pq;
    rr = 0;
    for (std::size_t m = 0; m < n; ++m) {
      g[m] += alpha * p[m];
      r[m] -= alpha * q[m];
      rr += r[m] * r[m];
    }
    st.iterations = it;
    if (rr <= target) break;
    double rz_new = 0;
    for (std::size_t m = 0; m < n; ++m) {
      z[m] = r[m] / diag[m];
      rz_new += r[m] * z[m];
    }
    const double beta = rz_new / rz;
    rz = rz_new;
    for (std::size_t m = 0; m < n; ++m) p[m] = z[m] + beta * p[m];
  }
  st.relative_residual = std::sqrt(rr / bb);
  if (!(st.relative_residual <= opt.max_residual))
    throw Error(what + ": the marker forces did not converge (relative residual " +
                std::to_string(st.relative_residual) + " after " + std::to_string(st.iterations) +
                " CG iterations; the sheet's velocity cannot be imposed)");
  return st;
}

}  // namespace finverse::cfd
