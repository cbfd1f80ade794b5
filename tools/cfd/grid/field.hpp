// Cell-centred scalar field on a StretchedGrid: u, v, w, p of the fractional-step solver and the
// work vectors of the multigrid solver.
//
// Storage is one contiguous array, x fastest, with `ghost` layers of ghost cells around the
// interior (none in z for 2-D fields). Interior indices run 0..n-1; ghosts are -ghost..-1 and
// n..n+ghost-1. The Poisson operator uses one ghost layer to realise periodic wrap-around and
// homogeneous boundary conditions without branches in its inner loops.
//
// Reductions (dot, norms) are summed per grid line in parallel and the line sums are then added in
// a fixed order, so results are bitwise identical for any OpenMP thread count (DESIGN.md section 3,
// determinism).
#pragma once

#include <cstddef>
#include <vector>

#include "cfd/grid/stretched_grid.hpp"

namespace finverse::cfd {

class Field {
 public:
  Field() = default;
  Field(int nx, int ny, int nz, int dim, int ghost = 1);
  explicit Field(const StretchedGrid& grid, int ghost = 1);

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  int nz() const { return nz_; }
  int dim() const { return dim_; }
  int ghost() const { return g_; }
  // Distance in the array between (i,j,k) and (i,j+1,k), (i,j,k+1).
  std::ptrdiff_t stride_y() const { return sx_; }
  std::ptrdiff_t stride_z() const { return sx_ * sy_; }
  std::size_t interior_size() const {
    return static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_) *
           static_cast<std::size_t>(nz_);
  }
  bool same_shape(const Field& o) const {
    return nx_ == o.nx_ && ny_ == o.ny_ && nz_ == o.nz_ && dim_ == o.dim_ && g_ == o.g_;
  }

  std::ptrdiff_t index(int i, int j, int k) const {
    return (i + g_) + sx_ * ((j + g_) + sy_ * static_cast<std::ptrdiff_t>(k + gz_));
  }
  double& operator()(int i, int j, int k) { return v_[static_cast<std::size_t>(index(i, j, k))]; }
  const double& operator()(int i, int j, int k) const {
    return v_[static_cast<std::size_t>(index(i, j, k))];
  }
  double* data() { return v_.data(); }
  const double* data() const { return v_.data(); }

  // Sets interior and ghosts.
  void fill(double value);

 private:
  int nx_ = 0, ny_ = 0, nz_ = 0, dim_ = 0, g_ = 0, gz_ = 0;
  std::ptrdiff_t sx_ = 0, sy_ = 0;
  std::vector<double> v_;
};

// Loops over fewer cells than this run serially: on coarse multigrid levels the fork/join of a
// parallel region costs more than the work, and on an oversubscribed machine far more.
inline constexpr long parallel_min_cells = 16384;

// Sum over the lines (j, k) of line(j, k) (each nx cells long), evaluated in parallel and added
// in a fixed order. The building block of every reduction that must not depend on the thread count.
template <class LineSum>
double ordered_line_sum(int nx, int ny, int nz, LineSum line) {
  const int lines = ny * nz;
  std::vector<double> part(static_cast<std::size_t>(lines));
#pragma omp parallel for schedule(static) if (static_cast<long>(nx) * lines >= parallel_min_cells)
  for (int l = 0; l < lines; ++l) part[static_cast<std::size_t>(l)] = line(l % ny, l / ny);
  double s = 0;
  for (double p : part) s += p;
  return s;
}

// Sum of term(i) over i in [0, n) in eight interleaved partial sums (i mod 8), added pairwise at
// the end: a fixed order, so the same bits on every call, but eight independent chains of
// additions instead of one. A single chain waits one addition's latency per term (a strict
// left-to-right sum cannot be vectorised without -ffast-math), which made the multigrid-CG inner
// products 8.5 % of a 2-D time step (perf, Turek-Hron CFD3, 1 thread).
template <class Term>
double lane_sum(int n, Term term) {
  double s[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  int i = 0;
  for (; i + 8 <= n; i += 8)
    for (int q = 0; q < 8; ++q) s[q] += term(i + q);
  for (int q = 0; i < n; ++i, ++q) s[q] += term(i);
  return ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
}

// Interior inner product and norms, deterministic (see above).
double dot(const Field& a, const Field& b);
double norm2(const Field& a);
double max_abs(const Field& a);
// y += alpha x and x = y + beta x over the interior, y, x of the same shape.
void axpy(double alpha, const Field& x, Field& y);
void xpby(const Field& y, double beta, Field& x);
void copy_interior(const Field& from, Field& to);

}  // namespace finverse::cfd
