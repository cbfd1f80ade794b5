// Linear-interpolation prolongation and its transpose as restriction; see grid_transfer.hpp.
#include "cfd/poisson/grid_transfer.hpp"

namespace finverse::cfd {

void GridTransfer::setup(const PoissonOperator& fine, const PoissonOperator& coarse,
                         const Coarsening& coarsening) {
  fine_ = &fine;
  coarse_ = &coarse;
  const StretchedGrid& fg = fine.grid();
  const StretchedGrid& cg = coarse.grid();
  for (int d = 0; d < 3; ++d) {
    const auto sd = static_cast<std::size_t>(d);
    const Axis& fa = fg.axis(d);
    const Axis& ca = cg.axis(d);
    const int nf = fa.size(), nc = ca.size();
    auto& pr = prol_[sd];
    pr.assign(static_cast<std::size_t>(nf), {});
    for (int i = 0; i < nf; ++i) {
      auto& e = pr[static_cast<std::size_t>(i)];
      const AxisCoarsening& m = coarsening[sd];
      const int I = m.parent[static_cast<std::size_t>(i)];
      if (d >= fg.dim() || m.children(I) == 1) {
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
      else if (fine.bc().periodic(d))
        xn = nb < 0 ? ca.centre(nc - 1) - ca.length() : ca.centre(0) + ca.length();
      else if (fine.bc()[static_cast<Side>(2 * d + (nb >= nc))] == BcType::Dirichlet)
        xn = nb < 0 ? ca.lo() : ca.hi();  // the wall, where the correction vanishes
      else {
        xn = xp;
        constant = true;  // Neumann: zero-gradient extension
      }
      const double wn = constant ? 0.0 : (xf - xp) / (xn - xp);
      e[0] = {I, 1.0 - wn};
      e[1] = {constant ? I : nb, wn};
    }
    std::vector<std::vector<std::pair<int, double>>> rs(static_cast<std::size_t>(nc));
    for (int i = 0; i < nf; ++i)
      for (const Entry& e : pr[static_cast<std::size_t>(i)]) {
        if (e.w == 0.0) continue;
        int C = e.c;
        if (C < 0 || C >= nc) {
          if (!fine.bc().periodic(d)) continue;  // the wall's zero value carries no residual
          C = (C + nc) % nc;
        }
        rs[static_cast<std::size_t>(C)].emplace_back(i, e.w);
      }
    rptr_[sd].assign(1, 0);
    ridx_[sd].clear();
    rw_[sd].clear();
    for (const auto& row : rs) {
      for (const auto& [i, w] : row) ridx_[sd].push_back(i), rw_[sd].push_back(w);
      rptr_[sd].push_back(static_cast<int>(ridx_[sd].size()));
    }
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
    return fine.bc().periodic(d) ? (c + n) % n : -1;  // -1: the wall value, always "present"
  };
#pragma omp parallel for schedule(static) if (static_cast<long>(fg.cells()) >= parallel_min_cells)
  for (int l = 0; l < fg.ny() * fg.nz(); ++l) {
    const int j = l % fg.ny(), k = l / fg.ny();
    for (int i = 0; i < fg.nx(); ++i) {
      if (!fine.active(i, j, k)) continue;
      double lost = 0;
      for (const Entry& ez : prol_[2][static_cast<std::size_t>(k)])
        for (const Entry& ey : prol_[1][static_cast<std::size_t>(j)])
          for (const Entry& ex : prol_[0][static_cast<std::size_t>(i)]) {
            const double w = ex.w * ey.w * ez.w;
            if (w == 0.0) continue;
            const int cx = wrap(ex.c, 0), cy = wrap(ey.c, 1), cz = wrap(ez.c, 2);
            if (cx < 0 || cy < 0 || cz < 0) continue;
            if (!coarse.active(cx, cy, cz)) lost += w;
          }
      scale_[fine.cell_index(i, j, k)] = lost < 1 - 1e-12 ? 1 / (1 - lost) : 0.0;
    }
  }
}

void GridTransfer::prolongate_add(Field& ce, Field& fx) const {
  coarse_->fill_ghosts(ce);
  const StretchedGrid& fg = fine_->grid();
  const int nx = fg.nx(), ny = fg.ny(), nz = fg.nz();
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
    const double* s = sc ? sc + static_cast<std::size_t>(nx) * static_cast<std::size_t>(l) : nullptr;
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
  const double* sc = scale_.empty() ? nullptr : scale_.data();
  const bool par = static_cast<long>(fg.cells()) >= parallel_min_cells;
  const auto row = [](std::size_t n, int j, int k, int ny) {
    return n * (static_cast<std::size_t>(j) + static_cast<std::size_t>(ny) * static_cast<std::size_t>(k));
  };
  double* tx = tx_.data();
  double* txy = txy_.data();
  // x: gather each fine line onto the coarse x positions (with the immersed-boundary scaling).
#pragma omp parallel for schedule(static) if (par)
  for (int l = 0; l < fny * fnz; ++l) {
    const int j = l % fny, k = l / fny;
    const double* r = &fr(0, j, k);
    const double* s = sc ? sc + row(static_cast<std::size_t>(fnx), j, k, fny) : nullptr;
    double* out = tx + row(static_cast<std::size_t>(cnx), j, k, fny);
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
  for (int l = 0; l < cny * fnz; ++l) {
    const int J = l % cny, k = l / cny;
    double* out = txy + row(static_cast<std::size_t>(cnx), J, k, cny);
    for (int I = 0; I < cnx; ++I) out[I] = 0;
    for (int q = rptr_[1][static_cast<std::size_t>(J)]; q < rptr_[1][static_cast<std::size_t>(J) + 1]; ++q) {
      const double w = rw_[1][static_cast<std::size_t>(q)];
      const double* in = tx + row(static_cast<std::size_t>(cnx), ridx_[1][static_cast<std::size_t>(q)], k, fny);
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
      const double* in = txy + row(static_cast<std::size_t>(cnx), J, ridx_[2][static_cast<std::size_t>(q)], cny);
      for (int I = 0; I < cnx; ++I) out[I] += w * in[I];
    }
    if (coarse_->active_cells() != cg.cells())
      for (int I = 0; I < cnx; ++I)
        if (!coarse_->active(I, J, K)) out[I] = 0;
  }
}

}  // namespace finverse::cfd
