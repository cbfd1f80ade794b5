// Geometric multigrid hierarchy and cycles; see multigrid.hpp.
#include "cfd/poisson/multigrid.hpp"

#include <sstream>
#include <stdexcept>

namespace finverse::cfd {


void Multigrid::setup(const PoissonOperator& fine, const MultigridOptions& options) {
  if (options.pre_sweeps < 0 || options.post_sweeps < 0 || options.pre_sweeps + options.post_sweeps == 0)
    throw std::invalid_argument("Multigrid: need at least one smoothing sweep");
  for (int d = 0; d < fine.dim(); ++d)
    if (fine.bc().periodic(d) && fine.grid().n(d) % 2 != 0 && fine.grid().cells() > options.coarsest_max_cells)
      throw std::invalid_argument("Multigrid: a periodic axis needs an even cell count (red-black colouring)");
  options_ = options;
  omega_ = options.relaxation > 0 ? options.relaxation : fine.dim() == 3 ? 1.2 : 1.0;
  ops_.assign(1, &fine);
  owned_.clear();
  transfers_.clear();
  coarsenings_.clear();
  while (static_cast<int>(ops_.size()) < options.max_levels) {
    const PoissonOperator& op = *ops_.back();
    if (op.grid().cells() <= options.coarsest_max_cells) break;
    Coarsening c = choose_coarsening(op, options.coarsening_ratio);
    if (!coarsens(c)) c = choose_coarsening(op, 0.0);  // nothing is narrow enough: halve anyway
    if (!coarsens(c)) break;
    owned_.push_back(std::make_unique<PoissonOperator>(coarsen_operator(op, c)));
    ops_.push_back(owned_.back().get());
    coarsenings_.push_back(std::move(c));
  }
  transfers_.resize(ops_.size() - 1);
  for (std::size_t l = 0; l + 1 < ops_.size(); ++l) transfers_[l].setup(*ops_[l], *ops_[l + 1], coarsenings_[l]);
  x_.clear();
  b_.clear();
  r_.clear();
  for (const PoissonOperator* op : ops_) {
    x_.push_back(op->make_field());
    b_.push_back(op->make_field());
    r_.push_back(op->make_field());
  }
  coarse_.setup(*ops_.back());
}

void Multigrid::cycle(const Field& b, Field& x) { cycle_level(0, b, x, options_.cycle); }

void Multigrid::cycle_level(int l, const Field& b, Field& x, CycleType type) {
  const auto sl = static_cast<std::size_t>(l);
  const PoissonOperator& op = *ops_[sl];
  if (l + 1 == levels()) {
    coarse_.solve(b, x);
    return;
  }
  const bool fuse = options_.smoother == SmootherKind::RedBlack && options_.pre_sweeps > 0;
  for (int s = 0; s < options_.pre_sweeps - (fuse ? 1 : 0); ++s) smooth(options_.smoother, op, b, x, true, omega_);
  if (fuse) red_black_sweep_residual(op, b, x, omega_, r_[sl]);
  else op.residual(b, x, r_[sl]);
  transfers_[sl].restrict_residual(r_[sl], b_[sl + 1]);
  x_[sl + 1].fill(0.0);
  switch (type) {
    case CycleType::V: cycle_level(l + 1, b_[sl + 1], x_[sl + 1], CycleType::V); break;
    case CycleType::W:
      cycle_level(l + 1, b_[sl + 1], x_[sl + 1], CycleType::W);
      cycle_level(l + 1, b_[sl + 1], x_[sl + 1], CycleType::W);
      break;
    case CycleType::F:
      cycle_level(l + 1, b_[sl + 1], x_[sl + 1], CycleType::F);
      cycle_level(l + 1, b_[sl + 1], x_[sl + 1], CycleType::V);
      break;
  }
  transfers_[sl].prolongate_add(x_[sl + 1], x);
  for (int s = 0; s < options_.post_sweeps; ++s) smooth(options_.smoother, op, b, x, false, omega_);
}

std::string Multigrid::describe() const {
  std::ostringstream s;
  for (std::size_t l = 0; l < ops_.size(); ++l) {
    const StretchedGrid& g = ops_[l]->grid();
    if (l) s << " -> ";
    s << g.nx() << 'x' << g.ny();
    if (g.dim() == 3) s << 'x' << g.nz();
  }
  s << " (direct)";
  return s.str();
}

}  // namespace finverse::cfd
