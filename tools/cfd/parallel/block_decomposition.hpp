// The flow grid split into blocks, one per MPI rank (issue 48, deliverable 2; docs/studies/flow_mpi.md).
//
// Pencils: every grid line along x stays whole on one rank, and the (y, z) plane of lines is cut
// into py x pz rectangles (pz = 1 in 2-D). Whole x lines keep three things rank-local and hence
// independent of the rank count: the zebra line smoother along x, the periodic wrap in x, and
// each line's partial sum of the line-ordered reductions (field.hpp). Blocks differ in size by
// at most one line per direction. Among the factorisations py x pz = ranks that give every block
// at least `min_lines` lines in each cut direction, the one with the fewest halo cells per rank
// (the largest block's perimeter times nx) is taken, ties to the larger py.
//
// Pure index arithmetic, no MPI: the halo exchange (halo_exchange.hpp) and the distributed grid
// (distributed_grid.hpp) build on it, and it is what refuses a rank count the grid cannot take.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "cfd/grid/line_range.hpp"

namespace finverse::cfd {

// One rank's lines: y in [j0, j1), z in [k0, k1), all of x.
using Block = LineRange;

class BlockDecomposition {
 public:
  BlockDecomposition() = default;
  // Throws finverse::Error naming the largest rank count that works when `ranks` cannot be split
  // with at least min_lines lines per block in each cut direction.
  BlockDecomposition(int nx, int ny, int nz, int dim, int ranks, int min_lines = 2);
  // Explicit block edges along y (py + 1 of them, 0 ... ny) and z (pz + 1, 0 ... nz).
  BlockDecomposition(int nx, int ny, int nz, int dim, std::vector<int> y_edges, std::vector<int> z_edges);

  // The same split with each edge moved to the nearest allowed position (sorted face indices;
  // a multigrid level's coarse faces, so that every level's blocks are whole coarse cells).
  // Throws when a block would get fewer than min_lines lines.
  BlockDecomposition snapped(const std::vector<int>& y_allowed, const std::vector<int>& z_allowed, int min_lines = 2) const;
  // The next multigrid level's split: each coarse cell to the block of its children. `parent`:
  // the coarse cell of each fine cell along y and z; every edge must fall between two coarse cells.
  BlockDecomposition coarsened(int coarse_nx, const std::vector<int>& y_parent, const std::vector<int>& z_parent) const;
  const std::vector<int>& y_edges() const { return ys_; }
  const std::vector<int>& z_edges() const { return zs_; }

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  int nz() const { return nz_; }
  int dim() const { return dim_; }
  int ranks() const { return py_ * pz_; }
  int py() const { return py_; }
  int pz() const { return pz_; }
  // Rank r sits at (r mod py, r / py) in the block grid.
  const Block& block(int rank) const { return blocks_.at(static_cast<std::size_t>(rank)); }
  // The rank across the block's face normal to `axis` (1: y, 2: z) on `side` (-1 or +1); -1 at a
  // domain edge that is not periodic. A periodic axis with one block is its own neighbour.
  int neighbour(int rank, int axis, int side, const std::array<bool, 3>& periodic) const;
  // The rank that owns line (j, k).
  int owner(int j, int k) const;
  // Cells a rank receives in one exchange of `ghost` layers (faces, edges and corners), the
  // largest over the ranks; 0 for one rank on non-periodic axes.
  std::size_t max_halo_cells(int ghost, const std::array<bool, 3>& periodic) const;

  // The largest rank count <= ranks that a grid of ny x nz lines can be split into.
  static int largest_feasible(int ny, int nz, int dim, int ranks, int min_lines = 2);

 private:
  void make_blocks();

  int nx_ = 0, ny_ = 0, nz_ = 0, dim_ = 0, py_ = 1, pz_ = 1;
  std::vector<int> ys_, zs_;  // block edges: ys_[0] = 0 ... ys_[py] = ny
  std::vector<Block> blocks_;
};

}  // namespace finverse::cfd
