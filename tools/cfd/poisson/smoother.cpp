// Red-black point and zebra line Gauss-Seidel smoothers; see smoother.hpp.
#include "cfd/poisson/smoother.hpp"

#include <algorithm>
#include <vector>

#include "cfd/poisson/stencil_lines.hpp"

namespace finverse::cfd {

namespace {

// The point update x_P = (b_P + sum_f T_f x_N) / diag_P of one colour on one grid line (j, k),
// over-relaxed by omega. Inactive cells have inverse diagonal 0 and stay at 0.
template <int D>
struct ColourLines {
  int nx, ny;
  const double *tx, *ty, *tz, *inv_diag;
  std::ptrdiff_t sy, sz;
  const Field* b;
  Field* x;
  double omega;

  explicit ColourLines(const PoissonOperator& op, const Field& rhs, Field& sol, double w)
      : nx(op.grid().nx()), ny(op.grid().ny()), tx(op.transmissibility(0).data()),
        ty(op.transmissibility(1).data()), tz(op.transmissibility(2).data()),
        inv_diag(op.inverse_diagonal().data()), sy(sol.stride_y()), sz(sol.stride_z()), b(&rhs), x(&sol),
        omega(w) {}

  void update(int j, int k, int colour) const {
    double* xc = &(*x)(0, j, k);
    const double* bb = &(*b)(0, j, k);
    const LineCoefficients c(tx, ty, tz, nx, ny, j, k);
    const double *txr = c.x_faces, *tys = c.y_lower, *tyn = c.y_upper, *tzb = c.z_lower, *tzt = c.z_upper;
    const double* inv = inv_diag + c.cell;
    for (int i = (j + k + colour) & 1; i < nx; i += 2) {
      double s = bb[i] + txr[i] * xc[i - 1] + txr[i + 1] * xc[i + 1] + tys[i] * xc[i - sy] +
                 tyn[i] * xc[i + sy];
      if constexpr (D == 3) s += tzb[i] * xc[i - sz] + tzt[i] * xc[i + sz];
      xc[i] = inv[i] > 0 ? xc[i] + omega * (s * inv[i] - xc[i]) : 0.0;
    }
  }
};

// Updates the cells of one colour everywhere.
template <int D>
void colour_update(const PoissonOperator& op, const Field& b, Field& x, int colour, double omega) {
  const ColourLines<D> lines(op, b, x, omega);
  const int ny = op.grid().ny(), nz = op.grid().nz();
#pragma omp parallel for schedule(static) if (static_cast<long>(op.grid().cells()) >= parallel_min_cells)
  for (int l = 0; l < ny * nz; ++l) lines.update(l % ny, l / ny, colour);
}

// Both colours in one pass over the grid: plane k gets the first colour, then plane k - 1 the
// second. Every update reads the same values as in two separate colour passes (the second colour
// of plane k - 1 needs the first colour of planes k - 2, k - 1 and k, all done; the first colour of
// plane k needs the second colour of plane k - 1 before its update, which comes after), so the
// result is bit for bit that of colour_update twice, while each plane's coefficients are read from
// memory once per sweep instead of twice: the smoother is bound by memory bandwidth on the fine
// grid. The first colour of line (j, k) and the second of line (j, k - 1) go to the same thread,
// which is all the ordering within a plane needs; one barrier per plane.
template <int D>
void fused_colours(const PoissonOperator& op, const Field& b, Field& x, int first, double omega) {
  const ColourLines<D> lines(op, b, x, omega);
  const int ny = op.grid().ny(), nz = op.grid().nz();
#pragma omp parallel if (static_cast<long>(op.grid().cells()) >= parallel_min_cells)
  for (int k = 0; k <= nz; ++k) {
#pragma omp for schedule(static)
    for (int j = 0; j < ny; ++j) {
      if (k < nz) lines.update(j, k, first);
      if (k > 0) lines.update(j, k - 1, 1 - first);
    }
  }
}

// fused_colours with the residual r = b - A x of the result: plane k - 2 is final once the
// second colour of plane k - 1 is, so its residual follows in the same pass while the plane is
// still in cache, instead of in a separate pass over the whole grid. Line (j, k - 2) reads x on
// lines (j +- 1, k - 2) and (j, k - 3), final since the previous plane's barrier, and (j, k - 1),
// whose second colour this thread has just updated; nothing writes plane k - 2 any more. Two
// extra passes of the plane loop finish the last planes (in 2-D, nz = 1, the residual then waits
// for the barrier after the second colour, as its lines read their neighbours j +- 1).
template <int D>
void fused_colours_residual(const PoissonOperator& op, const Field& b, Field& x, double omega, Field& r) {
  const ColourLines<D> lines(op, b, x, omega);
  const StencilLines<D, true> residual(op, &b, x, r);
  const int ny = op.grid().ny(), nz = op.grid().nz();
#pragma omp parallel if (static_cast<long>(op.grid().cells()) >= parallel_min_cells)
  for (int k = 0; k <= nz + 1; ++k) {
#pragma omp for schedule(static)
    for (int j = 0; j < ny; ++j) {
      if (k < nz) lines.update(j, k, 0);
      if (k > 0 && k <= nz) lines.update(j, k - 1, 1);
      if (k > 1) residual.line(j, k - 2);
    }
  }
}

// Solves the lines along axis `a` whose transverse index parity is `colour`. Each line is the
// tridiagonal system  diag_m x_m - T_{m} x_{m-1} - T_{m+1} x_{m+1} = b_m + transverse neighbours,
// with the wrap-around couplings of a periodic axis handled by the Sherman-Morrison formula.
// Inactive cells (diag 0) are held at zero by replacing their row with the identity.
template <int D>
void line_update(const PoissonOperator& op, const Field& b, Field& x, int a, int colour) {
  const StretchedGrid& g = op.grid();
  const int n[3] = {g.nx(), g.ny(), g.nz()};
  const int t1 = a == 0 ? 1 : 0, t2 = a == 2 ? 1 : 2;  // transverse axes
  const int m = n[a];
  const bool periodic = op.bc().periodic(a) && m > 2;
  const FaceCoefficients& beta = op.beta();
  const std::ptrdiff_t stride[3] = {1, x.stride_y(), x.stride_z()};
  const int lines = n[t1] * n[t2];
#pragma omp parallel if (static_cast<long>(g.cells()) >= parallel_min_cells)
  {
    std::vector<double> lo(static_cast<std::size_t>(m)), di(static_cast<std::size_t>(m)),
        up(static_cast<std::size_t>(m)), rhs(static_cast<std::size_t>(m)), u(static_cast<std::size_t>(m)),
        cp(static_cast<std::size_t>(m)), dp(static_cast<std::size_t>(m));
    auto thomas = [&](std::vector<double>& r, std::vector<double>& d) {
      // Solves (lo, di, up) y = r in place into r; d is scratch for the modified diagonal.
      d[0] = di[0];
      for (int q = 1; q < m; ++q) {
        const double w = lo[static_cast<std::size_t>(q)] / d[static_cast<std::size_t>(q - 1)];
        d[static_cast<std::size_t>(q)] = di[static_cast<std::size_t>(q)] - w * up[static_cast<std::size_t>(q - 1)];
        // A zero pivot means the line segment so far is a whole singular component (an
        // all-Neumann segment isolated by immersed-boundary faces); pinning it fixes its constant.
        if (d[static_cast<std::size_t>(q)] <= 1e-12 * di[static_cast<std::size_t>(q)])
          d[static_cast<std::size_t>(q)] = di[static_cast<std::size_t>(q)];
        r[static_cast<std::size_t>(q)] -= w * r[static_cast<std::size_t>(q - 1)];
      }
      r[static_cast<std::size_t>(m - 1)] /= d[static_cast<std::size_t>(m - 1)];
      for (int q = m - 2; q >= 0; --q)
        r[static_cast<std::size_t>(q)] = (r[static_cast<std::size_t>(q)] - up[static_cast<std::size_t>(q)] *
                                                                              r[static_cast<std::size_t>(q + 1)]) /
                                         d[static_cast<std::size_t>(q)];
    };
#pragma omp for schedule(static)
    for (int l = 0; l < lines; ++l) {
      int idx[3];
      idx[t1] = l % n[t1];
      idx[t2] = l / n[t1];
      if (((idx[t1] + idx[t2]) & 1) != colour) continue;
      double wrap = 0;  // transmissibility of the periodic closing face
      for (int q = 0; q < m; ++q) {
        idx[a] = q;
        const std::size_t c = op.cell_index(idx[0], idx[1], idx[2]);
        const auto sq = static_cast<std::size_t>(q);
        const double dg = op.diagonal()[c];
        // Faces along the line and the transverse neighbours' contribution to the right-hand side.
        int f[3] = {idx[0], idx[1], idx[2]};
        const double tlo = op.transmissibility(a)[beta.index(a, f[0], f[1], f[2])];
        f[a] += 1;
        const double thi = op.transmissibility(a)[beta.index(a, f[0], f[1], f[2])];
        double r = b(idx[0], idx[1], idx[2]);
        const double* xp = &x(idx[0], idx[1], idx[2]);
        for (int t : {t1, t2}) {
          if (t >= D) continue;
          int e[3] = {idx[0], idx[1], idx[2]};
          const double tl = op.transmissibility(t)[beta.index(t, e[0], e[1], e[2])];
          e[t] += 1;
          const double th = op.transmissibility(t)[beta.index(t, e[0], e[1], e[2])];
          r += tl * xp[-stride[t]] + th * xp[stride[t]];
        }
        if (dg > 0) {
          di[sq] = dg;
          lo[sq] = -tlo;
          up[sq] = -thi;
          rhs[sq] = r;
        } else {
          di[sq] = 1, lo[sq] = up[sq] = rhs[sq] = 0;
        }
        if (q == 0) wrap = tlo;
      }
      if (!periodic) {
        // Non-periodic ends: the boundary transmissibility stays in the diagonal only.
        lo[0] = 0;
        up[static_cast<std::size_t>(m - 1)] = 0;
        if (op.bc().periodic(a)) {
          // m <= 2 periodic: both couplings go to the same neighbour; fold them into the band.
          // For m == 1 the cell couples to itself and the net coupling is zero.
          if (m == 1) di[0] -= 2 * wrap;
          else {
            up[0] -= wrap;
            lo[1] -= wrap;
          }
        }
        thomas(rhs, cp);
      } else {
        // Cyclic tridiagonal: A = A' + u v^T with the corner entries -wrap moved into a rank-one
        // update (Sherman-Morrison), gamma chosen to keep A' well conditioned.
        const auto last = static_cast<std::size_t>(m - 1);
        const double corner = -wrap;  // A[0][m-1] = A[m-1][0]
        const double gamma = -di[0];
        const double d0 = di[0], dl = di[last];
        di[0] = d0 - gamma;
        di[last] = dl - corner * corner / gamma;
        lo[0] = 0;
        up[last] = 0;
        std::fill(u.begin(), u.end(), 0.0);
        u[0] = gamma;
        u[last] = corner;
        thomas(rhs, cp);
        thomas(u, cp);
        const double vy = rhs[0] + corner / gamma * rhs[last];
        const double vz = u[0] + corner / gamma * u[last];
        const double fac = vy / (1 + vz);
        for (std::size_t q = 0; q <= last; ++q) rhs[q] -= fac * u[q];
      }
      for (int q = 0; q < m; ++q) {
        idx[a] = q;
        x(idx[0], idx[1], idx[2]) = rhs[static_cast<std::size_t>(q)];
      }
    }
  }
}

template <int D>
void rb(const PoissonOperator& op, const Field& b, Field& x, bool forward, double omega) {
  // A periodic axis needs its ghost copies refreshed between the colours: two passes then.
  if (!op.bc().periodic(0) && !op.bc().periodic(1) && !op.bc().periodic(2)) {
    fused_colours<D>(op, b, x, forward ? 0 : 1, omega);
    return;
  }
  for (int c : {0, 1}) {
    op.fill_ghosts(x);
    colour_update<D>(op, b, x, forward ? c : 1 - c, omega);
  }
}

template <int D>
void zebra(const PoissonOperator& op, const Field& b, Field& x, bool forward) {
  for (int s = 0; s < D; ++s) {
    const int a = forward ? s : D - 1 - s;
    for (int c : {0, 1}) {
      op.fill_ghosts(x);
      line_update<D>(op, b, x, a, forward ? c : 1 - c);
    }
  }
}

}  // namespace

void red_black_sweep_residual(const PoissonOperator& op, const Field& b, Field& x, double omega, Field& r) {
  if (op.bc().periodic(0) || op.bc().periodic(1) || op.bc().periodic(2)) {
    red_black_sweep(op, b, x, true, omega);
    op.residual(b, x, r);
  } else if (op.dim() == 3) {
    fused_colours_residual<3>(op, b, x, omega, r);
  } else {
    fused_colours_residual<2>(op, b, x, omega, r);
  }
}

void red_black_sweep(const PoissonOperator& op, const Field& b, Field& x, bool forward, double omega) {
  if (op.dim() == 3) rb<3>(op, b, x, forward, omega);
  else rb<2>(op, b, x, forward, omega);
}

void red_black_colour(const PoissonOperator& op, const Field& b, Field& x, int colour, double omega) {
  if (op.dim() == 3) colour_update<3>(op, b, x, colour & 1, omega);
  else colour_update<2>(op, b, x, colour & 1, omega);
}

void zebra_line_sweep(const PoissonOperator& op, const Field& b, Field& x, bool forward) {
  if (op.dim() == 3) zebra<3>(op, b, x, forward);
  else zebra<2>(op, b, x, forward);
}

}  // namespace finverse::cfd
