// The pressure operator's connected components across MPI ranks (issue 48; docs/studies/
// flow_mpi.md): which active cells are joined through open faces, and which components touch no
// Dirichlet face (singular: p fixed only up to a constant there). The serial operator finds them
// by union-find on the whole grid (poisson_operator.cpp, build_connectivity); here each rank
// joins its block's cells, labels each local set by its smallest global cell index and whether it
// is pinned, and the ranks then exchange the labels across their block sides (open faces only)
// and keep the smaller label and the "or" of the pins until nothing changes (as many rounds as
// blocks on the longest path through a component). The global ids follow the labels' order,
// which is the serial operator's order (components numbered by their first active cell in scan
// order), so component c here is component c there.
#pragma once

#include <vector>

#include "cfd/parallel/distributed_poisson.hpp"

namespace finverse::cfd {

class DistributedComponents {
 public:
  // Collective.
  explicit DistributedComponents(const DistributedPoisson& op);

  // The component of this rank's cell (i, j, k) (local indices; -1 inactive), as the whole grid's
  // operator numbers it.
  int component(int i, int j, int k) const;
  // The components of the block's line (j, k), nx of them: the hot loops read a line at a time.
  const int* line(int j, int k) const { return id_.data() + static_cast<std::size_t>(nx_) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(ny_) * k); }
  int components() const { return static_cast<int>(singular_.size()); }
  bool singular(int c) const { return singular_[static_cast<std::size_t>(c)] != 0; }
  bool any_singular() const;
  // Rounds of label exchange it took.
  int rounds() const { return rounds_; }

 private:
  int nx_ = 0, ny_ = 0;
  std::vector<int> id_;         // per local cell
  std::vector<char> singular_;  // per global component
  int rounds_ = 0;
};

}  // namespace finverse::cfd
