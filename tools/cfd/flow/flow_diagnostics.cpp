// Diagnostics of the flow state: divergence of the face velocities (continuity), kinetic energy and
// momentum (conservation checks in a periodic box), and the convective CFL number (fluid cells
// only where a body is immersed). Sums are
// ordered per grid line (field.hpp), so they are bitwise independent of the thread count.
#include <algorithm>
#include <cmath>

#include "cfd/flow/flow_solver.hpp"
#include "cfd/parallel/rank_share.hpp"

namespace finverse::cfd {

double FlowSolver::max_divergence() const {
  double m = 0;  // a maximum: the same in any order (reported every step, so over the threads too)
  // On a rank's own lines while the face velocities are partial, then over the ranks (rank_lines.cpp).
  const LineRange lines = partial_ ? faces_ : all_lines(grid_);
  const int nx = grid_.nx(), ny = lines.ny(), count = ny * lines.nz();
#pragma omp parallel for schedule(static) reduction(max : m) if (static_cast<long>(nx) * count >= parallel_min_cells)
  for (int l = 0; l < count; ++l) {
    const int j = lines.j0 + l % ny, k = lines.k0 + l / ny;
    for (int i = 0; i < nx; ++i)
      if (fluid(i, j, k) && !cut_cell(i, j, k)) m = std::max(m, std::abs(divergence(U_, i, j, k)));
  }
  if (cut_) m = std::max(m, cut_residual_max_);
  return partial_ ? rank_share()->max(m) : m;
}

double FlowSolver::kinetic_energy() const {
  return ordered_line_sum(grid_.nx(), grid_.ny(), grid_.nz(), [&](int j, int k) {
    double s = 0;
    for (int i = 0; i < grid_.nx(); ++i) {
      double q = 0;
      for (int c = 0; c < dim(); ++c) q += u_[static_cast<std::size_t>(c)](i, j, k) * u_[static_cast<std::size_t>(c)](i, j, k);
      s += 0.5 * grid_.volume(i, j, k) * q;
    }
    return s;
  });
}

double FlowSolver::momentum(int c) const {
  const Field& u = u_[static_cast<std::size_t>(c)];
  return ordered_line_sum(grid_.nx(), grid_.ny(), grid_.nz(), [&](int j, int k) {
    double s = 0;
    for (int i = 0; i < grid_.nx(); ++i) s += grid_.volume(i, j, k) * u(i, j, k);
    return s;
  });
}

double FlowSolver::cfl(double dt) const {
  double m = 0;  // a maximum: the same in any order, so for any number of threads
  const int nx = grid_.nx(), ny = grid_.ny(), nz = grid_.nz();
#pragma omp parallel for schedule(static) reduction(max : m) if (static_cast<long>(grid_.cells()) >= parallel_min_cells)
  for (int l = 0; l < ny * nz; ++l) {
    const int j = l % ny, k = l / ny;
    for (int i = 0; i < nx; ++i) {
      if (!fluid(i, j, k)) continue;  // ghost values are reflections, not velocities
      double s = 0;
      for (int d = 0; d < dim(); ++d)
        s += std::abs(u_[static_cast<std::size_t>(d)](i, j, k)) / grid_.axis(d).width(d == 0 ? i : d == 1 ? j : k);
      m = std::max(m, s);
    }
  }
  return dt * m;
}

}  // namespace finverse::cfd
