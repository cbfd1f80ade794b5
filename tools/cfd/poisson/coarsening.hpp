// Choice of the next multigrid level on a stretched grid: which cells of each axis are merged.
//
// On a stretched grid the cell aspect ratio reaches 10-40 in the far field, and the coupling of a
// cell to its neighbours is strongest across its shortest dimension (transmissibility ~ A/d). A
// point smoother then only damps error that oscillates along the strongly coupled directions, so
// the next level may only be coarser in those directions: semi-coarsening (Dendy, Mulder). On a
// tensor-product grid the strong directions of a cell follow from its widths alone, so the
// decision can be made per axis and per cell of that axis:
//
//     merge neighbours i, i+1 along axis d  iff  max(h_i, h_{i+1}) <= ratio * h_min,
//
// with h_min the smallest width of the current level over all axes. Cells much wider than the
// finest cells stay unmerged until the levels have coarsened the rest to their size, so every
// level is close to isotropic where it is coarsened and the point smoother is a good smoother
// everywhere ("coarsening towards isotropy"). A uniform grid is halved on every axis, as before.
//
// A periodic axis is halved whole or not at all (its count must stay a multiple of 2 on every
// smoothed level for the red-black colouring to close across the wrap-around).
#pragma once

#include <array>
#include <vector>

#include "cfd/grid/stretched_grid.hpp"
#include "cfd/poisson/poisson_operator.hpp"

namespace finverse::cfd {

// The merge pattern of one axis: coarse cell C consists of fine cells first[C] .. first[C+1]-1
// (one or two of them).
struct AxisCoarsening {
  std::vector<int> first;   // size coarse + 1, first.back() = fine cell count
  std::vector<int> parent;  // coarse cell of each fine cell

  static AxisCoarsening identity(int n);
  static AxisCoarsening pairs(const std::vector<bool>& merge_with_next);
  int fine_cells() const { return static_cast<int>(parent.size()); }
  int coarse_cells() const { return static_cast<int>(first.size()) - 1; }
  int children(int c) const { return first[static_cast<std::size_t>(c) + 1] - first[static_cast<std::size_t>(c)]; }
  bool merges() const { return coarse_cells() < fine_cells(); }
};

using Coarsening = std::array<AxisCoarsening, 3>;

// The merge pattern of the next level (see above); `ratio` <= 0 halves every axis that can be.
// No axis merging anything means coarsening has to stop.
Coarsening choose_coarsening(const PoissonOperator& op, double ratio);
// The same from the grid and the conditions alone (the whole grid's hierarchy, known to every MPI
// rank without the whole grid's operator).
Coarsening choose_coarsening(const StretchedGrid& grid, const BoundaryConditions& bc, double ratio);
bool coarsens(const Coarsening& c);

// The coarse grid (faces of the fine grid at the coarse cell boundaries) and the rediscretised
// coarse operator: beta averaged over the fine faces that make up each coarse face, weighted by
// face area (stretching, variable coefficients and immersed-boundary masks carry down).
StretchedGrid coarsen_grid(const StretchedGrid& fine, const Coarsening& c);
PoissonOperator coarsen_operator(const PoissonOperator& fine, const Coarsening& c);
// The coarse beta alone (coarse grid cg = coarsen_grid(g, c)); on an MPI rank's block with the
// block's part of the coarsening it is the whole grid's coarse beta on the block's faces.
FaceCoefficients coarsen_beta(const StretchedGrid& g, const FaceCoefficients& beta, const Coarsening& c,
                              const StretchedGrid& cg);

}  // namespace finverse::cfd
