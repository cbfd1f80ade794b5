// The Poisson operator's 5/7-point stencil applied along one grid line (j, k):
//     out_i = b_i - (A p)_i   (WithB)   or   out_i = (A p)_i,
//     (A p)_i = diag_i p_i - sum over the faces of T_f p_neighbour   (poisson_operator.hpp).
// One kernel for PoissonOperator::apply / residual and for the smoother that fuses the residual
// into its last sweep (smoother.hpp), so that both give the same bits.
#pragma once

#include <cstddef>

#include "cfd/grid/field.hpp"
#include "cfd/poisson/poisson_operator.hpp"

namespace finverse::cfd {

// Where line (j, k)'s coefficients start: its x faces (nx + 1 of them), its lower and upper y and
// z faces and its cells (offset `cell` into any per-cell array such as the diagonal).
struct LineCoefficients {
  const double *x_faces, *y_lower, *y_upper, *z_lower, *z_upper;
  std::size_t cell;

  LineCoefficients(const double* tx, const double* ty, const double* tz, int nx, int ny, int j, int k) {
    const auto l = static_cast<std::size_t>(j) + static_cast<std::size_t>(ny) * static_cast<std::size_t>(k);
    x_faces = tx + static_cast<std::size_t>(nx + 1) * l;
    y_lower = ty + static_cast<std::size_t>(nx) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(ny + 1) * k);
    y_upper = y_lower + nx;
    z_lower = tz + static_cast<std::size_t>(nx) * l;
    z_upper = z_lower + static_cast<std::size_t>(nx) * ny;
    cell = static_cast<std::size_t>(nx) * l;
  }
};

template <int D, bool WithB>
struct StencilLines {
  int nx, ny;
  const double *tx, *ty, *tz, *diag;
  std::ptrdiff_t sy, sz;
  const Field* b;  // null unless WithB
  const Field* p;
  Field* out;

  StencilLines(const PoissonOperator& op, const Field* rhs, const Field& x, Field& result)
      : nx(op.grid().nx()), ny(op.grid().ny()), tx(op.transmissibility(0).data()),
        ty(op.transmissibility(1).data()), tz(op.transmissibility(2).data()), diag(op.diagonal().data()),
        sy(x.stride_y()), sz(x.stride_z()), b(rhs), p(&x), out(&result) {}

  void line(int j, int k) const {
    const double* pc = &(*p)(0, j, k);
    double* o = &(*out)(0, j, k);
    const double* bb = WithB ? &(*b)(0, j, k) : nullptr;
    const LineCoefficients c(tx, ty, tz, nx, ny, j, k);
    const double *txr = c.x_faces, *tys = c.y_lower, *tyn = c.y_upper, *tzb = c.z_lower, *tzt = c.z_upper;
    const double* d = diag + c.cell;
    for (int i = 0; i < nx; ++i) {
      double a = d[i] * pc[i] - txr[i] * pc[i - 1] - txr[i + 1] * pc[i + 1] - tys[i] * pc[i - sy] -
                 tyn[i] * pc[i + sy];
      if constexpr (D == 3) a -= tzb[i] * pc[i - sz] + tzt[i] * pc[i + sz];
      if constexpr (WithB) o[i] = bb[i] - a;
      else o[i] = a;
    }
  }
};

}  // namespace finverse::cfd
