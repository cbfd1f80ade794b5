// The pressure multigrid over MPI ranks; see distributed_multigrid.hpp.
#include "cfd/parallel/distributed_multigrid.hpp"

#include <mpi.h>

#include <string>

#include "core/error.hpp"

namespace finverse::cfd {

struct DistributedMultigrid::Level {
  std::unique_ptr<DistributedGrid> own_grid;   // levels >= 1
  std::unique_ptr<DistributedPoisson> own_op;  // levels >= 1
  const DistributedGrid* grid = nullptr;
  const DistributedPoisson* op = nullptr;
  GridTransfer transfer;  // this level -> the next (levels < D)
  Field x, b, r;
};

WholeHierarchy whole_hierarchy(const StretchedGrid& whole, const BoundaryConditions& bc, const MultigridOptions& options) {
  // Multigrid::setup's loop, on the grids alone.
  WholeHierarchy h;
  h.grids.push_back(whole);
  while (static_cast<int>(h.grids.size()) < options.max_levels) {
    const StretchedGrid& g = h.grids.back();
    if (g.cells() <= options.coarsest_max_cells) break;
    Coarsening c = choose_coarsening(g, bc, options.coarsening_ratio);
    if (!coarsens(c)) c = choose_coarsening(g, bc, 0.0);
    if (!coarsens(c)) break;
    h.grids.push_back(coarsen_grid(g, c));
    h.coarsenings.push_back(std::move(c));
  }
  return h;
}

MultigridSplit plan_multigrid_split(const WholeHierarchy& h, int ranks, int min_lines) {
  const StretchedGrid& fine = h.grids.front();
  for (int D = static_cast<int>(h.grids.size()) - 1; D >= 0; --D) {
    const StretchedGrid& g = h.grids[static_cast<std::size_t>(D)];
    if (BlockDecomposition::largest_feasible(g.ny(), g.nz(), g.dim(), ranks, min_lines) != ranks) continue;
    const BlockDecomposition at_d(g.nx(), g.ny(), g.nz(), g.dim(), ranks, min_lines);
    std::vector<int> ys = at_d.y_edges(), zs = at_d.z_edges();
    for (int l = D - 1; l >= 0; --l) {  // each coarse edge to its first fine child's face
      const Coarsening& c = h.coarsenings[static_cast<std::size_t>(l)];
      for (int& e : ys) e = c[1].first[static_cast<std::size_t>(e)];
      for (int& e : zs) e = c[2].first[static_cast<std::size_t>(e)];
    }
    return {BlockDecomposition(fine.nx(), fine.ny(), fine.nz(), fine.dim(), ys, zs), D};
  }
  BlockDecomposition(fine.nx(), fine.ny(), fine.nz(), fine.dim(), ranks, min_lines);  // throws with the advice
  throw Error("multigrid split: no level can be split into " + std::to_string(ranks) + " ranks");
}

Coarsening block_coarsening(const Coarsening& whole, int j0, int j1, int k0, int k1, int dim) {
  const auto part = [](const AxisCoarsening& m, int lo, int hi) {
    AxisCoarsening b;
    const int LO = m.parent[static_cast<std::size_t>(lo)], HI = m.parent[static_cast<std::size_t>(hi - 1)] + 1;
    for (int C = LO; C <= HI; ++C) b.first.push_back(m.first[static_cast<std::size_t>(C)] - lo);
    for (int i = lo; i < hi; ++i) b.parent.push_back(m.parent[static_cast<std::size_t>(i)] - LO);
    return b;
  };
  return {whole[0], part(whole[1], j0, j1), dim == 3 ? part(whole[2], k0, k1) : whole[2]};
}

namespace {

// Every rank's block faces onto `root`'s whole-grid coefficients (faces shared by two blocks
// hold the same value on both).
FaceCoefficients gather_beta(const DistributedGrid& g, const FaceCoefficients& local, const StretchedGrid& whole, int root) {
  FaceCoefficients out(whole, 0.0);
  const auto& d = g.decomposition();
  for (int a = 0; a < whole.dim(); ++a) {
    const std::vector<double>& mine = local.values(a);
    std::vector<int> counts(static_cast<std::size_t>(d.ranks())), displs(static_cast<std::size_t>(d.ranks()));
    int total = 0;
    for (int r = 0; r < d.ranks(); ++r) {
      const Block& b = d.block(r);
      counts[static_cast<std::size_t>(r)] = (d.nx() + (a == 0)) * (b.ny() + (a == 1)) * (b.nz() + (a == 2));
      displs[static_cast<std::size_t>(r)] = total;
      total += counts[static_cast<std::size_t>(r)];
    }
    std::vector<double> all(g.rank() == root ? static_cast<std::size_t>(total) : 0);
    MPI_Gatherv(mine.data(), static_cast<int>(mine.size()), MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE,
                root, g.communicator());
    if (g.rank() != root) continue;
    for (int r = 0; r < d.ranks(); ++r) {
      const Block& b = d.block(r);
      std::size_t q = static_cast<std::size_t>(displs[static_cast<std::size_t>(r)]);
      for (int k = 0; k < b.nz() + (a == 2); ++k)
        for (int j = 0; j < b.ny() + (a == 1); ++j)
          for (int i = 0; i < d.nx() + (a == 0); ++i) out(a, i, j + b.j0, k + b.k0) = all[q++];
    }
  }
  return out;
}

}  // namespace

DistributedMultigrid::DistributedMultigrid(const DistributedPoisson& fine, const WholeHierarchy& hierarchy, int gathered_level,
                                           const MultigridOptions& options, long serial_below_cells)
    : hierarchy_(hierarchy), options_(options), gathered_(gathered_level) {
  if (options.smoother != SmootherKind::RedBlack)
    throw Error("distributed multigrid: only the red-black smoother runs on MPI ranks (the zebra lines along y and z do not)");
  if (options.pre_sweeps < 0 || options.post_sweeps < 0 || options.pre_sweeps + options.post_sweeps == 0)
    throw Error("distributed multigrid: need at least one smoothing sweep");
  const int D = gathered_level;
  if (D < 0 || D >= levels()) throw Error("distributed multigrid: the gathered level is outside the hierarchy");
  const StretchedGrid& whole = hierarchy.grids.front();
  const BoundaryConditions& bc = fine.bc_whole();
  omega_ = options.relaxation > 0 ? options.relaxation : whole.dim() == 3 ? 1.2 : 1.0;
  const int dim = whole.dim();
  levels_.push_back(std::make_unique<Level>());
  levels_[0]->grid = &fine.grid(), levels_[0]->op = &fine;
  for (int l = 1; l <= D; ++l) {
    auto lv = std::make_unique<Level>();
    const Level& up = *levels_.back();
    const Coarsening& c = hierarchy.coarsenings[static_cast<std::size_t>(l - 1)];
    const StretchedGrid& g = hierarchy.grids[static_cast<std::size_t>(l)];
    lv->own_grid = std::make_unique<DistributedGrid>(up.grid->communicator(),
                                                     up.grid->decomposition().coarsened(g.nx(), c[1].parent, c[2].parent),
                                                     up.grid->periodic());
    const Block &fb = up.grid->block(), &cb = lv->own_grid->block();
    const Coarsening local = block_coarsening(c, fb.j0, fb.j1, fb.k0, fb.k1, dim);
    lv->own_op = std::make_unique<DistributedPoisson>(
        *lv->own_grid, g, coarsen_beta(up.op->block_grid(), up.op->block_operator().beta(), local, g.block(cb.j0, cb.j1, cb.k0, cb.k1)),
        bc);
    lv->grid = lv->own_grid.get(), lv->op = lv->own_op.get();
    levels_.push_back(std::move(lv));
  }
  for (int l = 0; l < D; ++l) {
    Level& f = *levels_[static_cast<std::size_t>(l)];
    const Level& c = *levels_[static_cast<std::size_t>(l) + 1];
    const auto& fo = f.op->block_operator();
    const auto& co = c.op->block_operator();
    int inactive = fo.active_cells() != fo.grid().cells() || co.active_cells() != co.grid().cells();
    MPI_Allreduce(MPI_IN_PLACE, &inactive, 1, MPI_INT, MPI_MAX, f.grid->communicator());
    BlockTransferInfo info;
    info.fine_whole = &hierarchy.grids[static_cast<std::size_t>(l)];
    info.coarse_whole = &hierarchy.grids[static_cast<std::size_t>(l) + 1];
    info.coarsening = &hierarchy.coarsenings[static_cast<std::size_t>(l)];
    info.bc = &bc;
    info.fine_offset = {f.grid->block().j0, f.grid->block().k0};
    info.coarse_offset = {c.grid->block().j0, c.grid->block().k0};
    const DistributedGrid* fg = f.grid;
    const DistributedGrid* cg = c.grid;
    info.exchange_fine = [fg](Field& x) { fg->exchange(x); };
    info.exchange_coarse = [cg](Field& x) { cg->exchange(x); };
    info.any_inactive = inactive != 0;
    f.transfer.setup_block(fo, co, info);
  }
  for (auto& lv : levels_) lv->x = lv->grid->make_field(1), lv->b = lv->grid->make_field(1), lv->r = lv->grid->make_field(1);
  // Level D's whole operator on rank 0; below it, the serial cycle there, or (a large level D on
  // many ranks) the levels below on half the ranks, agglomerated.
  const Level& last = *levels_.back();
  const StretchedGrid& gd = hierarchy.grids[static_cast<std::size_t>(D)];
  const FaceCoefficients beta = gather_beta(*last.grid, last.op->block_operator().beta(), gd, 0);
  gb_ = std::make_unique<Field>(gd, 1), gx_ = std::make_unique<Field>(gd, 1);
  if (agglomerate(beta, bc, serial_below_cells)) return;
  if (last.grid->rank() == 0) {
    whole_gathered_ = std::make_unique<PoissonOperator>();
    whole_gathered_->setup(gd, beta, bc);
    MultigridOptions sub = options;
    sub.max_levels = options.max_levels - D;
    coarse_mg_ = std::make_unique<Multigrid>();
    coarse_mg_->setup(*whole_gathered_, sub);
  }
}

// Levels D and below on the first half of the ranks (a sub-communicator), as a multigrid of their
// own, when level D is too large for rank 0 alone: the pattern of agglomerating coarse levels onto
// fewer ranks (AMReX's MLMG), with the redistribution through rank 0 (level D gathered there and
// scattered over the half; a direct all-to-all is the next step). Collective; false: no
// agglomeration (level D small, or the half cannot split it on a level below).
bool DistributedMultigrid::agglomerate(const FaceCoefficients& beta, const BoundaryConditions& bc, long serial_below_cells) {
  const Level& last = *levels_.back();
  const DistributedGrid& g = *last.grid;
  const StretchedGrid& gd = hierarchy_.grids[static_cast<std::size_t>(gathered_)];
  if (g.size() < 2 || static_cast<long>(gd.cells()) <= serial_below_cells) return false;
  const int half = BlockDecomposition::largest_feasible(gd.ny(), gd.nz(), gd.dim(), g.size() / 2);
  if (half < 2) return false;
  auto sub = std::make_unique<WholeHierarchy>();
  sub->grids.assign(hierarchy_.grids.begin() + gathered_, hierarchy_.grids.end());
  sub->coarsenings.assign(hierarchy_.coarsenings.begin() + gathered_, hierarchy_.coarsenings.end());
  const MultigridSplit split = plan_multigrid_split(*sub, half);
  if (split.gathered_level < 1) return false;
  MPI_Comm comm = MPI_COMM_NULL;
  MPI_Comm_split(g.communicator(), g.rank() < half ? 0 : MPI_UNDEFINED, g.rank(), &comm);
  sub_hierarchy_ = std::move(sub);
  if (comm == MPI_COMM_NULL) return true;
  sub_comm_ = comm;
  // The whole level-D coefficients to the half (rank 0 has them), each rank cutting its block.
  FaceCoefficients whole_beta = beta;
  for (int a = 0; a < gd.dim(); ++a)
    MPI_Bcast(&whole_beta(a, 0, 0, 0), static_cast<int>(whole_beta.values(a).size()), MPI_DOUBLE, 0, comm);
  sub_grid_ = std::make_unique<DistributedGrid>(comm, split.fine, g.periodic());
  const Block& b = sub_grid_->block();
  sub_op_ = std::make_unique<DistributedPoisson>(*sub_grid_, gd, block_faces(whole_beta, gd.block(b.j0, b.j1, b.k0, b.k1), b), bc);
  MultigridOptions options = options_;
  options.max_levels = options_.max_levels - gathered_;
  sub_mg_ = std::make_unique<DistributedMultigrid>(*sub_op_, *sub_hierarchy_, split.gathered_level, options, serial_below_cells);
  sub_b_ = std::make_unique<Field>(sub_grid_->make_field(1)), sub_x_ = std::make_unique<Field>(sub_grid_->make_field(1));
  return true;
}

DistributedMultigrid::~DistributedMultigrid() {
  sub_mg_.reset(), sub_op_.reset(), sub_grid_.reset();
  if (sub_comm_ != MPI_COMM_NULL) MPI_Comm_free(&sub_comm_);
}

void DistributedMultigrid::cycle(const Field& b, Field& x) { cycle_level(0, b, x, options_.cycle); }
void DistributedMultigrid::cycle(const Field& b, Field& x, CycleType type) { cycle_level(0, b, x, type); }

void DistributedMultigrid::gathered_cycle(const Field& b, Field& x, CycleType type) {
  const DistributedGrid& g = *levels_.back()->grid;
  g.gather(b, *gb_);
  g.gather(x, *gx_);
  if (sub_hierarchy_) {  // agglomerated: the half's own multigrid (the other ranks wait in the scatter)
    if (sub_mg_) {
      sub_grid_->scatter(*gb_, *sub_b_);
      sub_grid_->scatter(*gx_, *sub_x_);
      sub_mg_->cycle(*sub_b_, *sub_x_, type);
      sub_grid_->gather(*sub_x_, *gx_);
    }
  } else if (g.rank() == 0) {
    coarse_mg_->cycle(*gb_, *gx_, type);
  }
  g.scatter(*gx_, x);
}

// Multigrid::cycle_level with the block operations; level D goes to rank 0.
void DistributedMultigrid::cycle_level(int l, const Field& b, Field& x, CycleType type) {
  if (l == gathered_) {
    gathered_cycle(b, x, type);
    return;
  }
  Level& lv = *levels_[static_cast<std::size_t>(l)];
  Level& next = *levels_[static_cast<std::size_t>(l) + 1];
  const bool fuse = options_.pre_sweeps > 0;
  for (int s = 0; s < options_.pre_sweeps - (fuse ? 1 : 0); ++s) lv.op->red_black_sweep(b, x, true, omega_);
  if (fuse) lv.op->red_black_sweep_residual(b, x, omega_, lv.r);
  else lv.op->residual(b, x, lv.r);
  lv.grid->exchange(lv.r);
  lv.transfer.restrict_residual(lv.r, next.b);
  next.x.fill(0.0);
  switch (type) {
    case CycleType::V: cycle_level(l + 1, next.b, next.x, CycleType::V); break;
    case CycleType::W:
      cycle_level(l + 1, next.b, next.x, CycleType::W);
      cycle_level(l + 1, next.b, next.x, CycleType::W);
      break;
    case CycleType::F:
      cycle_level(l + 1, next.b, next.x, CycleType::F);
      cycle_level(l + 1, next.b, next.x, CycleType::V);
      break;
  }
  lv.transfer.prolongate_add(next.x, x);
  for (int s = 0; s < options_.post_sweeps; ++s) lv.op->red_black_sweep(b, x, false, omega_);
}

}  // namespace finverse::cfd
