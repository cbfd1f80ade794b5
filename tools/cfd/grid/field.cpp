// Field storage and deterministic interior reductions; see field.hpp.
#include "cfd/grid/field.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace finverse::cfd {

Field::Field(int nx, int ny, int nz, int dim, int ghost)
    : nx_(nx), ny_(ny), nz_(nz), dim_(dim), g_(ghost), gz_(dim == 3 ? ghost : 0) {
  if (nx < 1 || ny < 1 || nz < 1 || ghost < 0 || (dim != 2 && dim != 3) || (dim == 2 && nz != 1))
    throw std::invalid_argument("Field: bad shape");
  sx_ = nx + 2 * g_;
  sy_ = ny + 2 * g_;
  const std::ptrdiff_t sz = nz + 2 * gz_;
  v_.assign(static_cast<std::size_t>(sx_ * sy_ * sz), 0.0);
}

Field::Field(const StretchedGrid& grid, int ghost)
    : Field(grid.nx(), grid.ny(), grid.nz(), grid.dim(), ghost) {}

void Field::fill(double value) { std::fill(v_.begin(), v_.end(), value); }

double dot(const Field& a, const Field& b) {
  return ordered_line_sum(a.nx(), a.ny(), a.nz(), [&](int j, int k) {
    const double* pa = &a(0, j, k);
    const double* pb = &b(0, j, k);
    return lane_sum(a.nx(), [&](int i) { return pa[i] * pb[i]; });
  });
}

double norm2(const Field& a) { return std::sqrt(dot(a, a)); }

double max_abs(const Field& a) {
  // max is exact in floating point, so any order gives the same answer.
  double m = 0;
#pragma omp parallel for reduction(max : m) schedule(static) \
    if (static_cast<long>(a.interior_size()) >= parallel_min_cells)
  for (int l = 0; l < a.ny() * a.nz(); ++l) {
    const double* p = &a(0, l % a.ny(), l / a.ny());
    for (int i = 0; i < a.nx(); ++i) m = std::max(m, std::abs(p[i]));
  }
  return m;
}

namespace {
template <class Op>
void for_lines(const Field& shape, Op op) {
#pragma omp parallel for schedule(static) if (static_cast<long>(shape.interior_size()) >= parallel_min_cells)
  for (int l = 0; l < shape.ny() * shape.nz(); ++l) op(l % shape.ny(), l / shape.ny());
}
}  // namespace

void axpy(double alpha, const Field& x, Field& y) {
  for_lines(y, [&](int j, int k) {
    const double* px = &x(0, j, k);
    double* py = &y(0, j, k);
    for (int i = 0; i < y.nx(); ++i) py[i] += alpha * px[i];
  });
}

void xpby(const Field& y, double beta, Field& x) {
  for_lines(x, [&](int j, int k) {
    const double* py = &y(0, j, k);
    double* px = &x(0, j, k);
    for (int i = 0; i < x.nx(); ++i) px[i] = py[i] + beta * px[i];
  });
}

void copy_interior(const Field& from, Field& to) {
  for_lines(to, [&](int j, int k) {
    const double* pf = &from(0, j, k);
    double* pt = &to(0, j, k);
    for (int i = 0; i < to.nx(); ++i) pt[i] = pf[i];
  });
}

}  // namespace finverse::cfd
