// The explicit kernels on a rank's own lines in a whole-flow MPI run (issue 48; the reasoning and
// measurements: docs/studies/flow_mpi.md, "The right-hand sides and the face velocities on the
// ranks' own lines"). A rank computes the face velocities of the cells of its two systems' blocks
// (faces_) plus every domain boundary face (the outlet balance sums them all), and the convective
// term on its momentum block (own_): exactly what its right-hand sides and the next step read.
// Cell velocities, p and phi stay whole. The rest is gathered only when a file needs it.
#include <stdexcept>
#include <string>

#include "cfd/flow/flow_solver.hpp"
#include "cfd/parallel/rank_share.hpp"

namespace finverse::cfd {

void FlowSolver::choose_rank_lines() {
  const LineRange all = all_lines(grid_);
  LineRange own = all, faces = all;
  // A closed body's ghost cells, cut cells and momentum rows reach across the blocks: whole.
  if (rank_lines_wanted_ && rank_share() && !ib_ && !cut_ && !pressure_stale_) {
    const LineRange m = helmholtz_[0].rhs_lines();
    bool same = true;
    for (int c = 1; c < dim(); ++c) same = same && helmholtz_[static_cast<std::size_t>(c)].rhs_lines() == m;
    if (same) own = m, faces = span(m, poisson_.rhs_lines());
  }
  // A step on other lines reads the last step's face velocities and convective term beyond them.
  // The gather is collective: the ranks agree first whether any of them needs it.
  if (partial_ && rank_share()->max(own == own_ && faces == faces_ ? 0.0 : 1.0) > 0) gather_rank_lines();
  own_ = own;
  faces_ = faces;
  partial_ = !(own == all && faces == all);
}

void FlowSolver::gather_rank_lines() {
  if (!partial_) return;
  partial_ = false;  // (first: a failed gather leaves nothing that claims to be partial)
  const RankShare& share = *rank_share();
  const int nx = grid_.nx();
  for (int d = 0; d < dim(); ++d) {
    // The face rows of faces_'s cells: their upper faces along d too (two blocks share those).
    const LineRange rows{faces_.j0, faces_.j1 + (d == 1), faces_.k0, faces_.k1 + (d == 2)};
    allgather_lines(share, rows, static_cast<std::size_t>(nx + (d == 0)),
                    [&](int j, int k) { return &U_(d, 0, j, k); });
  }
  for (int c = 0; c < dim(); ++c) {
    Field& n = conv_old_[static_cast<std::size_t>(c)];
    allgather_lines(share, own_, static_cast<std::size_t>(nx), [&](int j, int k) { return &n(0, j, k); });
  }
}

void FlowSolver::require_whole(const char* what) const {
  if (partial_)
    throw std::logic_error(std::string("flow solver: ") + what +
                           " read while the face velocities are the rank's own lines only (gather_rank_lines first)");
}

}  // namespace finverse::cfd
