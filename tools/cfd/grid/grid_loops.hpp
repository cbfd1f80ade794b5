// Parallel loops over the cells and faces of a grid for the flow solver's kernels: lines (j, k)
// are distributed over OpenMP threads, i runs innermost (contiguous). Each iteration writes only
// its own cell or face, so the results do not depend on the thread count.
#pragma once

#include "cfd/grid/field.hpp"
#include "cfd/grid/stretched_grid.hpp"

namespace finverse::cfd {

// fn(i, j, k) for every interior cell.
template <class Fn>
void for_each_cell(const StretchedGrid& g, Fn fn) {
  const int nx = g.nx(), ny = g.ny(), nz = g.nz();
#pragma omp parallel for schedule(static) if (static_cast<long>(g.cells()) >= parallel_min_cells)
  for (int l = 0; l < ny * nz; ++l) {
    const int j = l % ny, k = l / ny;
    for (int i = 0; i < nx; ++i) fn(i, j, k);
  }
}

// fn(j, k) for every grid line of cells along x (the kernel runs i itself, contiguous in memory).
template <class Fn>
void for_each_line(const StretchedGrid& g, Fn fn) {
  const int ny = g.ny(), nz = g.nz();
#pragma omp parallel for schedule(static) if (static_cast<long>(g.cells()) >= parallel_min_cells)
  for (int l = 0; l < ny * nz; ++l) fn(l % ny, l / ny);
}

// fn(i, j, k) for every face normal to axis d (i, j or k runs to n(d) along d).
template <class Fn>
void for_each_face(const StretchedGrid& g, int d, Fn fn) {
  const int ex = g.nx() + (d == 0), ey = g.ny() + (d == 1), ez = g.nz() + (d == 2);
#pragma omp parallel for schedule(static) if (static_cast<long>(g.cells()) >= parallel_min_cells)
  for (int l = 0; l < ey * ez; ++l) {
    const int j = l % ey, k = l / ey;
    for (int i = 0; i < ex; ++i) fn(i, j, k);
  }
}

}  // namespace finverse::cfd
