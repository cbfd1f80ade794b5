// Parallel loops over the cells and faces of a grid for the flow solver's kernels: lines (j, k)
// are distributed over OpenMP threads, i runs innermost (contiguous). Each iteration writes only
// its own cell or face, so the results do not depend on the thread count.
//
// A LineRange restricts a loop to a rectangle of lines: on MPI ranks that each hold the whole
// flow, the kernels whose output only the rank's own block is read from (the right-hand sides
// that the ranks' systems take their block of) run over that block alone. Each line's arithmetic
// is the same, so the block's values are the whole loop's bit for bit (docs/studies/flow_mpi.md,
// "The right-hand sides and the face velocities on the ranks' own lines").
#pragma once

#include "cfd/grid/field.hpp"
#include "cfd/grid/line_range.hpp"
#include "cfd/grid/stretched_grid.hpp"

namespace finverse::cfd {

// fn(j, k) for every grid line of cells along x in `lines` (the kernel runs i itself, contiguous
// in memory).
template <class Fn>
void for_each_line(const StretchedGrid& g, const LineRange& lines, Fn fn) {
  const int ny = lines.ny(), count = ny * lines.nz();
#pragma omp parallel for schedule(static) if (static_cast<long>(g.nx()) * count >= parallel_min_cells)
  for (int l = 0; l < count; ++l) fn(lines.j0 + l % ny, lines.k0 + l / ny);
}

template <class Fn>
void for_each_line(const StretchedGrid& g, Fn fn) {
  for_each_line(g, all_lines(g), fn);
}

// fn(i, j, k) for every interior cell of `lines` (all of them without).
template <class Fn>
void for_each_cell(const StretchedGrid& g, const LineRange& lines, Fn fn) {
  const int nx = g.nx();
  for_each_line(g, lines, [&](int j, int k) {
    for (int i = 0; i < nx; ++i) fn(i, j, k);
  });
}

template <class Fn>
void for_each_cell(const StretchedGrid& g, Fn fn) {
  for_each_cell(g, all_lines(g), fn);
}

// fn(i, j, k) for every face normal to axis d of the cells of `lines`, their upper faces included
// (i, j or k runs to n(d) along d at the grid's end).
template <class Fn>
void for_each_face(const StretchedGrid& g, int d, const LineRange& lines, Fn fn) {
  const int ex = g.nx() + (d == 0), j0 = lines.j0, k0 = lines.k0;
  const int ey = lines.ny() + (d == 1), ez = lines.nz() + (d == 2);
#pragma omp parallel for schedule(static) if (static_cast<long>(g.nx()) * ey * ez >= parallel_min_cells)
  for (int l = 0; l < ey * ez; ++l) {
    const int j = j0 + l % ey, k = k0 + l / ey;
    for (int i = 0; i < ex; ++i) fn(i, j, k);
  }
}

// fn(i, j, k) for every face normal to axis d (i, j or k runs to n(d) along d).
template <class Fn>
void for_each_face(const StretchedGrid& g, int d, Fn fn) {
  for_each_face(g, d, all_lines(g), fn);
}

}  // namespace finverse::cfd
