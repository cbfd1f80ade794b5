// Geometric multigrid for the cell-centred Poisson operator on stretched grids.
//
// Hierarchy: each level merges neighbouring cells along the axes where they are strongly coupled,
// i.e. where the cells are not much wider than the level's narrowest cells (coarsening.hpp): full
// coarsening on uniform grids, semi-coarsening towards isotropy on stretched ones, which keeps the
// point smoother effective on grids with far-field aspect ratios of 10-40 (iteration counts:
// docs/studies/poisson_multigrid.md).
// Coarse operators are rediscretised from face-area-averaged beta (coarsen_operator), which
// carries stretching and immersed-boundary masks down.
// Coarsening stops once a level has at most `coarsest_max_cells` cells or no axis can be halved;
// that level is solved exactly (CoarseSolver).
//
// Cycles: V, W or F with `pre` forward and `post` backward smoothing sweeps. With equal sweep
// counts, V and W cycles are symmetric positive (semi-)definite maps: usable as a preconditioner
// for conjugate gradients (poisson_solver.hpp).
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "cfd/poisson/coarse_solver.hpp"
#include "cfd/grid/field.hpp"
#include "cfd/poisson/poisson_operator.hpp"
#include "cfd/poisson/smoother.hpp"
#include "cfd/poisson/grid_transfer.hpp"

namespace finverse::cfd {

enum class CycleType { V, W, F };

struct MultigridOptions {
  CycleType cycle = CycleType::V;
  SmootherKind smoother = SmootherKind::RedBlack;
  int pre_sweeps = 2;
  int post_sweeps = 2;
  std::size_t coarsest_max_cells = 1024;
  // Cells are merged along an axis where both are at most this many times the level's narrowest
  // width (coarsening.hpp); <= 0 halves every axis regardless of stretching.
  double coarsening_ratio = 2.0;
  // Over-relaxation of the red-black point smoother; 0 picks the measured best: 1.2 in 3-D and 1
  // (Gauss-Seidel) in 2-D (docs/studies/poisson_multigrid.md). Symmetric for any omega in (0, 2).
  double relaxation = 0.0;
  int max_levels = 32;
};

class Multigrid {
 public:
  // `fine` must outlive the Multigrid.
  void setup(const PoissonOperator& fine, const MultigridOptions& options);

  // One cycle for A x = b on the finest level; x is the initial guess on entry.
  void cycle(const Field& b, Field& x);
  // The same with the cycle's type given: the coarse part of a cycle whose finer levels run
  // elsewhere (the distributed multigrid's levels below its gathered one).
  void cycle(const Field& b, Field& x, CycleType type) { cycle_level(0, b, x, type); }

  int levels() const { return static_cast<int>(ops_.size()); }
  const PoissonOperator& level_operator(int l) const { return *ops_[static_cast<std::size_t>(l)]; }
  const MultigridOptions& options() const { return options_; }
  // e.g. "128x128x128 -> 64x64x64 -> ... -> 8x8x8 (direct)".
  std::string describe() const;

 private:
  void cycle_level(int l, const Field& b, Field& x, CycleType type);

  MultigridOptions options_;
  std::vector<const PoissonOperator*> ops_;
  std::vector<std::unique_ptr<PoissonOperator>> owned_;
  std::vector<GridTransfer> transfers_;  // transfers_[l]: level l <-> l+1
  std::vector<Coarsening> coarsenings_;  // coarsenings_[l]: level l -> l+1
  std::vector<Field> x_, b_, r_;         // per level work (x_, b_ unused on level 0)
  CoarseSolver coarse_;
  double omega_ = 1.0;
};

}  // namespace finverse::cfd
