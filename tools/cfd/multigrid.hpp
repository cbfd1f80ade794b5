// Geometric multigrid for the cell-centred Poisson operator on stretched grids.
//
// Hierarchy: each level halves every axis that has an even cell count of at least 4 (a periodic
// axis needs a multiple of 4 so every smoothed level stays 2-colourable); axes that cannot be
// halved are kept (semi-coarsening). Coarse operators are rediscretised from face-area-averaged
// beta (PoissonOperator::coarsened), which carries stretching and immersed-boundary masks down.
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

#include "cfd/coarse_solver.hpp"
#include "cfd/field.hpp"
#include "cfd/poisson_operator.hpp"
#include "cfd/smoother.hpp"
#include "cfd/transfer.hpp"

namespace finverse::cfd {

enum class CycleType { V, W, F };

struct MultigridOptions {
  CycleType cycle = CycleType::V;
  SmootherKind smoother = SmootherKind::RedBlack;
  int pre_sweeps = 2;
  int post_sweeps = 2;
  std::size_t coarsest_max_cells = 1024;
  int max_levels = 32;
};

class Multigrid {
 public:
  // `fine` must outlive the Multigrid.
  void setup(const PoissonOperator& fine, const MultigridOptions& options);

  // One cycle for A x = b on the finest level; x is the initial guess on entry.
  void cycle(const Field& b, Field& x);

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
  std::vector<Field> x_, b_, r_;         // per level work (x_, b_ unused on level 0)
  CoarseSolver coarse_;
};

}  // namespace finverse::cfd
