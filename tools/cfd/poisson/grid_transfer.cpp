// Linear-interpolation prolongation and its transpose as restriction; see grid_transfer.hpp.
#include "cfd/poisson/grid_transfer.hpp"

#include <stdexcept>

namespace finverse::cfd {

namespace {

using Entries = std::array<GridTransfer::Entry, 2>;
using Rows = std::vector<std::vector<std::pair<int, double>>>;

// The 1-D prolongation of axis d on the whole grid: per fine cell its parent and the coarse
// neighbour on its side with their weights; -1 or nc for the ghost beyond a wall or the wrap.
std::vector<Entries> axis_prolongation(const Axis& fa, const Axis& ca, const AxisCoarsening& m, const BoundaryConditions& bc,
                                       int d, int dim) {
  const int nf = fa.size(), nc = ca.size();
  std::vector<Entries> pr(static_cast<std::size_t>(nf));
  for (int i = 0; i < nf; ++i) {
    auto& e = pr[static_cast<std::size_t>(i)];
    const int I = m.parent[static_cast<std::size_t>(i)];
    if (d >= dim || m.children(I) == 1) {
      e[0] = {I, 1.0};
      e[1] = {I, 0.0};
      continue;
    }
    const bool low_child = i == m.first[static_cast<std::size_t>(I)];
    const int nb = low_child ? I - 1 : I + 1;  // coarse neighbour on the fine cell's side
    const double xf = fa.centre(i), xp = ca.centre(I);
    double xn;
    bool constant = false;
    if (nb >= 0 && nb < nc) xn = ca.centre(nb);
    else if (bc.periodic(d))
      xn = nb < 0 ? ca.centre(nc - 1) - ca.length() : ca.centre(0) + ca.length();
    else if (bc[static_cast<Side>(2 * d + (nb >= nc))] == BcType::Dirichlet)
      xn = nb < 0 ? ca.lo() : ca.hi();  // the wall, where the correction vanishes
    else {
      xn = xp;
      constant = true;  // Neumann: zero-gradient extension
    }
    const double wn = constant ? 0.0 : (xf - xp) / (xn - xp);
    e[0] = {I, 1.0 - wn};
    e[1] = {constant ? I : nb, wn};
  }
  return pr;
}

// R = P^T of one axis: per coarse cell the fine cells and weights, in increasing fine index.
Rows axis_rows(const std::vector<Entries>& pr, int nc, bool periodic) {
  Rows rs(static_cast<std::size_t>(nc));
  for (std::size_t i = 0; i < pr.size(); ++i)
    for (const GridTransfer::Entry& e : pr[i]) {
      if (e.w == 0.0) continue;
      int C = e.c;
      if (C < 0 || C >= nc) {
        if (!periodic) continue;  // the wall's zero value carries no residual
        C = (C + nc) % nc;
      }
      rs[static_cast<std::size_t>(C)].emplace_back(static_cast<int>(i), e.w);
    }
  return rs;
}

}  // namespace

// The renormalisation of fine cell (i, j, k): 1 / (1 - the weight its prolongation puts on
// inactive coarse cells), 0 where nothing active is left. coarse_cell(c, d) maps an entry's coarse
// index along d to the one to look at (-1: the wall, always present); inactive(cx, cy, cz).
template <class CoarseCell, class Inactive>
double GridTransfer::renormalisation(int i, int j, int k, CoarseCell coarse_cell, Inactive inactive) const {
  double lost = 0;
  for (const Entry& ez : prol_[2][static_cast<std::size_t>(k)])
    for (const Entry& ey : prol_[1][static_cast<std::size_t>(j)])
      for (const Entry& ex : prol_[0][static_cast<std::size_t>(i)]) {
        const double w = ex.w * ey.w * ez.w;
        if (w == 0.0) continue;
        const int cx = coarse_cell(ex.c, 0), cy = coarse_cell(ey.c, 1), cz = coarse_cell(ez.c, 2);
        if (cx == kWall || cy == kWall || cz == kWall) continue;
        if (inactive(cx, cy, cz)) lost += w;
      }
  return lost < 1 - 1e-12 ? 1 / (1 - lost) : 0.0;
}

void GridTransfer::set_rows(int d, const std::vector<std::vector<std::pair<int, double>>>& rows) {
  const auto sd = static_cast<std::size_t>(d);
  rptr_[sd].assign(1, 0);
  ridx_[sd].clear();
  rw_[sd].clear();
  for (const auto& row : rows) {
    for (const auto& [i, w] : row) ridx_[sd].push_back(i), rw_[sd].push_back(w);
    rptr_[sd].push_back(static_cast<int>(ridx_[sd].size()));
  }
}

void GridTransfer::setup(const PoissonOperator& fine, const PoissonOperator& coarse,
                         const Coarsening& coarsening) {
  fine_ = &fine;
  coarse_ = &coarse;
  pad_y_ = pad_z_ = 0;
  exchange_coarse_ = nullptr;
  const StretchedGrid& fg = fine.grid();
  const StretchedGrid& cg = coarse.grid();
  for (int d = 0; d < 3; ++d) {
    const auto sd = static_cast<std::size_t>(d);
    prol_[sd] = axis_prolongation(fg.axis(d), cg.axis(d), coarsening[sd], fine.bc(), d, fg.dim());
    set_rows(d, axis_rows(prol_[sd], cg.n(d), fine.bc().periodic(d)));
  }
  tx_.assign(static_cast<std::size_t>(cg.nx()) * fg.ny() * fg.nz(), 0.0);
  txy_.assign(static_cast<std::size_t>(cg.nx()) * cg.ny() * fg.nz(), 0.0);

  // Renormalisation around immersed bodies: weights of inactive coarse cells are removed and the
  // rest scaled to sum to one; inactive fine cells get scale 0.
  scale_.clear();
  if (fine.active_cells() == fg.cells() && coarse.active_cells() == cg.cells()) return;
  scale_.assign(fg.cells(), 0.0);
  const auto wrap = [&](int c, int d) {
    const int n = cg.n(d);
    if (c >= 0 && c < n) return c;
    return fine.bc().periodic(d) ? (c + n) % n : kWall;  // the wall value, always "present"
  };
  const auto inactive = [&](int cx, int cy, int cz) { return !coarse.active(cx, cy, cz); };
#pragma omp parallel for schedule(static) if (static_cast<long>(fg.cells()) >= parallel_min_cells)
  for (int l = 0; l < fg.ny() * fg.nz(); ++l) {
    const int j = l % fg.ny(), k = l / fg.ny();
    for (int i = 0; i < fg.nx(); ++i)
      if (fine.active(i, j, k)) scale_[fine.cell_index(i, j, k)] = renormalisation(i, j, k, wrap, inactive);
  }
}

void GridTransfer::setup_block(const PoissonOperator& fine, const PoissonOperator& coarse, const BlockTransferInfo& info) {
  fine_ = &fine;
  coarse_ = &coarse;
  const StretchedGrid& fg = fine.grid();
  const StretchedGrid& cg = coarse.grid();
  const int dim = fg.dim();
  pad_y_ = 1, pad_z_ = dim == 3 ? 1 : 0;
  exchange_coarse_ = info.exchange_coarse;
  const int fo[3] = {0, info.fine_offset[0], info.fine_offset[1]}, co[3] = {0, info.coarse_offset[0], info.coarse_offset[1]};
  for (int d = 0; d < 3; ++d) {
    const auto sd = static_cast<std::size_t>(d);
    const auto whole = axis_prolongation(info.fine_whole->axis(d), info.coarse_whole->axis(d), (*info.coarsening)[sd], *info.bc,
                                         d, dim);
    const int nf_whole = info.fine_whole->n(d), nc_whole = info.coarse_whole->n(d);
    const auto rows = axis_rows(whole, nc_whole, info.bc->periodic(d));
    // This block's cells, coarse indices relative to the block (-1 and n: the ghosts, a
    // neighbour's or the wall's or the wrap's, which the exchange or the wall fills).
    prol_[sd].assign(static_cast<std::size_t>(fg.n(d)), {});
    for (int i = 0; i < fg.n(d); ++i) {
      auto e = whole[static_cast<std::size_t>(i + fo[d])];
      for (auto& x : e) x.c -= co[d];
      prol_[sd][static_cast<std::size_t>(i)] = e;
    }
    // The block's coarse cells' rows, in the whole grid's order; fine cells one beyond the block
    // (a neighbour's or across the wrap) as the ghost indices -1 and n.
    Rows local(static_cast<std::size_t>(cg.n(d)));
    const int nfl = fg.n(d);
    for (int C = 0; C < cg.n(d); ++C)
      for (const auto& [f, w] : rows[static_cast<std::size_t>(C + co[d])]) {
        int q = f - fo[d];
        if (q < -1 || q > nfl) q = q < 0 ? q + nf_whole : q - nf_whole;  // across the periodic wrap
        if (q < -1 || q > nfl)
          throw std::invalid_argument("GridTransfer::setup_block: a restriction row reaches beyond the block's ghosts");
        local[static_cast<std::size_t>(C)].emplace_back(q, w);
      }
    set_rows(d, local);
  }
  tx_.assign(static_cast<std::size_t>(cg.nx()) * (fg.ny() + 2 * pad_y_) * (fg.nz() + 2 * pad_z_), 0.0);
  txy_.assign(static_cast<std::size_t>(cg.nx()) * cg.ny() * (fg.nz() + 2 * pad_z_), 0.0);
  block_scale(info);
}

// The block's renormalisation: whether a coarse cell across the block's side is active comes from
// its owner (an exchanged 0/1 field), and the fine scale of the ghost rows the restriction reads
// from theirs. Collective through the exchanges (every rank calls it, all or none immersed).
void GridTransfer::block_scale(const BlockTransferInfo& info) {
  scale_.clear();
  if (!info.any_inactive) return;
  const StretchedGrid& fg = fine_->grid();
  const StretchedGrid& cg = coarse_->grid();
  Field active(cg.nx(), cg.ny(), cg.nz(), cg.dim(), 1), scale(fg.nx(), fg.ny(), fg.nz(), fg.dim(), 1);
  for (int k = 0; k < cg.nz(); ++k)
    for (int j = 0; j < cg.ny(); ++j)
      for (int i = 0; i < cg.nx(); ++i) active(i, j, k) = coarse_->active(i, j, k) ? 1.0 : 0.0;
  coarse_->fill_ghosts(active);
  info.exchange_coarse(active);
  const int co[3] = {0, info.coarse_offset[0], info.coarse_offset[1]};
  const auto local = [&](int c, int d) {  // a neighbour's or the wrap's ghost, or the wall
    const int g = c + co[d];
    return (g >= 0 && g < info.coarse_whole->n(d)) || info.bc->periodic(d) || d >= cg.dim() ? c : kWall;
  };
  const auto inactive = [&](int cx, int cy, int cz) { return active(cx, cy, cz) == 0.0; };
  for (int k = 0; k < fg.nz(); ++k)
    for (int j = 0; j < fg.ny(); ++j)
      for (int i = 0; i < fg.nx(); ++i)
        if (fine_->active(i, j, k)) scale(i, j, k) = renormalisation(i, j, k, local, inactive);
  fine_->fill_ghosts(scale);
  info.exchange_fine(scale);
  const int py = pad_y_, pz = pad_z_, ny = fg.ny() + 2 * py;
  scale_.assign(static_cast<std::size_t>(fg.nx()) * ny * (fg.nz() + 2 * pz), 0.0);
  for (int k = -pz; k < fg.nz() + pz; ++k)
    for (int j = -py; j < fg.ny() + py; ++j)
      for (int i = 0; i < fg.nx(); ++i)
        scale_[static_cast<std::size_t>(i) + static_cast<std::size_t>(fg.nx()) * (static_cast<std::size_t>(j + py) +
                                                                              static_cast<std::size_t>(ny) * (k + pz))] = scale(i, j, k);
}

void GridTransfer::prolongate_add(Field& ce, Field& fx) const {
  coarse_->fill_ghosts(ce);
  if (exchange_coarse_) exchange_coarse_(ce);  // a block: the neighbours' coarse cells
  const StretchedGrid& fg = fine_->grid();
  const int nx = fg.nx(), ny = fg.ny(), nz = fg.nz();
  const std::size_t sny = static_cast<std::size_t>(ny + 2 * pad_y_);
  const double* sc = scale_.empty() ? nullptr : scale_.data();
#pragma omp parallel for schedule(static) if (static_cast<long>(fg.cells()) >= parallel_min_cells)
  for (int l = 0; l < ny * nz; ++l) {
    const int j = l % ny, k = l / ny;
    const auto& ey = prol_[1][static_cast<std::size_t>(j)];
    const auto& ez = prol_[2][static_cast<std::size_t>(k)];
    const double* all_rows[4] = {&ce(0, ey[0].c, ez[0].c), &ce(0, ey[1].c, ez[0].c), &ce(0, ey[0].c, ez[1].c),
                                 &ce(0, ey[1].c, ez[1].c)};
    const double all_w[4] = {ey[0].w * ez[0].w, ey[1].w * ez[0].w, ey[0].w * ez[1].w, ey[1].w * ez[1].w};
    // Only the coarse rows with a weight: in 2-D (and next to a one-child coarse cell) half of
    // them have none, and adding their exact zero changed nothing but the time.
    const double* row[4];
    double wyz[4];
    int rows = 0;
    for (int q = 0; q < 4; ++q)
      if (all_w[q] != 0.0) row[rows] = all_rows[q], wyz[rows++] = all_w[q];
    double* out = &fx(0, j, k);
    const double* s =
        sc ? sc + static_cast<std::size_t>(nx) * (static_cast<std::size_t>(j + pad_y_) + sny * static_cast<std::size_t>(k + pad_z_))
           : nullptr;
    for (int i = 0; i < nx; ++i) {
      const auto& ex = prol_[0][static_cast<std::size_t>(i)];
      double v = 0;
      for (int q = 0; q < rows; ++q) v += wyz[q] * (ex[0].w * row[q][ex[0].c] + ex[1].w * row[q][ex[1].c]);
      out[i] += s ? s[i] * v : v;
    }
  }
}

void GridTransfer::restrict_residual(const Field& fr, Field& cb) const {
  const StretchedGrid& cg = coarse_->grid();
  const StretchedGrid& fg = fine_->grid();
  const int cnx = cg.nx(), cny = cg.ny(), cnz = cg.nz();
  const int fnx = fg.nx(), fny = fg.ny(), fnz = fg.nz();
  // A block also reads the fine rows one beyond it (the residual's ghosts, exchanged by the
  // caller): pad_y_, pad_z_ extra rows and planes on each side of the scratch arrays.
  const int py = pad_y_, pz = pad_z_;
  const int tny = fny + 2 * py, tnz = fnz + 2 * pz;
  const double* sc = scale_.empty() ? nullptr : scale_.data();
  const bool par = static_cast<long>(fg.cells()) >= parallel_min_cells;
  const auto row = [](std::size_t n, int j, int k, int ny) {
    return n * (static_cast<std::size_t>(j) + static_cast<std::size_t>(ny) * static_cast<std::size_t>(k));
  };
  double* tx = tx_.data();
  double* txy = txy_.data();
  // x: gather each fine line onto the coarse x positions (with the immersed-boundary scaling).
#pragma omp parallel for schedule(static) if (par)
  for (int l = 0; l < tny * tnz; ++l) {
    const int j = l % tny - py, k = l / tny - pz;
    const double* r = &fr(0, j, k);
    const double* s = sc ? sc + row(static_cast<std::size_t>(fnx), j + py, k + pz, tny) : nullptr;
    double* out = tx + row(static_cast<std::size_t>(cnx), j + py, k + pz, tny);
    const int* ptr = rptr_[0].data();
    const int* idx = ridx_[0].data();
    const double* w = rw_[0].data();
    for (int I = 0; I < cnx; ++I) {
      double v = 0;
      if (s)
        for (int q = ptr[I]; q < ptr[I + 1]; ++q) v += w[q] * s[idx[q]] * r[idx[q]];
      else
        for (int q = ptr[I]; q < ptr[I + 1]; ++q) v += w[q] * r[idx[q]];
      out[I] = v;
    }
  }
  // y: coarse row (J, k) = sum of weighted fine rows (j, k); contiguous in I.
#pragma omp parallel for schedule(static) if (par)
  for (int l = 0; l < cny * tnz; ++l) {
    const int J = l % cny, k = l / cny;  // k: padded plane index
    double* out = txy + row(static_cast<std::size_t>(cnx), J, k, cny);
    for (int I = 0; I < cnx; ++I) out[I] = 0;
    for (int q = rptr_[1][static_cast<std::size_t>(J)]; q < rptr_[1][static_cast<std::size_t>(J) + 1]; ++q) {
      const double w = rw_[1][static_cast<std::size_t>(q)];
      const double* in = tx + row(static_cast<std::size_t>(cnx), ridx_[1][static_cast<std::size_t>(q)] + py, k, tny);
      for (int I = 0; I < cnx; ++I) out[I] += w * in[I];
    }
  }
  // z: likewise into the coarse right-hand side; inactive coarse cells get none.
#pragma omp parallel for schedule(static) if (par)
  for (int l = 0; l < cny * cnz; ++l) {
    const int J = l % cny, K = l / cny;
    double* out = &cb(0, J, K);
    for (int I = 0; I < cnx; ++I) out[I] = 0;
    for (int q = rptr_[2][static_cast<std::size_t>(K)]; q < rptr_[2][static_cast<std::size_t>(K) + 1]; ++q) {
      const double w = rw_[2][static_cast<std::size_t>(q)];
      const double* in = txy + row(static_cast<std::size_t>(cnx), J, ridx_[2][static_cast<std::size_t>(q)] + pz, cny);
      for (int I = 0; I < cnx; ++I) out[I] += w * in[I];
    }
    if (coarse_->active_cells() != cg.cells())
      for (int I = 0; I < cnx; ++I)
        if (!coarse_->active(I, J, K)) out[I] = 0;
  }
}

}  // namespace finverse::cfd
