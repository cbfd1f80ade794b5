// Linear-interpolation prolongation and its transpose as restriction; see transfer.hpp.
#include "cfd/transfer.hpp"

namespace finverse::cfd {

void GridTransfer::setup(const PoissonOperator& fine, const PoissonOperator& coarse,
                         const std::array<bool, 3>& coarsened) {
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
      if (!coarsened[sd] || d >= fg.dim()) {
        e[0] = {i, 1.0};
        e[1] = {i, 0.0};
        continue;
      }
      const int I = i / 2;
      const int nb = (i % 2 == 0) ? I - 1 : I + 1;  // coarse neighbour on the fine cell's side
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
    auto& rs = restr_[sd];
    rs.assign(static_cast<std::size_t>(nc), {});
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
  }

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
  for (int k = 0; k < fg.nz(); ++k)
    for (int j = 0; j < fg.ny(); ++j)
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
    const double* row[4] = {&ce(0, ey[0].c, ez[0].c), &ce(0, ey[1].c, ez[0].c), &ce(0, ey[0].c, ez[1].c),
                            &ce(0, ey[1].c, ez[1].c)};
    const double wyz[4] = {ey[0].w * ez[0].w, ey[1].w * ez[0].w, ey[0].w * ez[1].w, ey[1].w * ez[1].w};
    double* out = &fx(0, j, k);
    const double* s = sc ? sc + static_cast<std::size_t>(nx) * static_cast<std::size_t>(l) : nullptr;
    for (int i = 0; i < nx; ++i) {
      const auto& ex = prol_[0][static_cast<std::size_t>(i)];
      double v = 0;
      for (int q = 0; q < 4; ++q) v += wyz[q] * (ex[0].w * row[q][ex[0].c] + ex[1].w * row[q][ex[1].c]);
      out[i] += s ? s[i] * v : v;
    }
  }
}

void GridTransfer::restrict_residual(const Field& fr, Field& cb) const {
  const StretchedGrid& cg = coarse_->grid();
  const int nx = cg.nx(), ny = cg.ny(), nz = cg.nz();
  const int fnx = fine_->grid().nx();
  const double* sc = scale_.empty() ? nullptr : scale_.data();
  const int fny = fine_->grid().ny();
#pragma omp parallel for schedule(static) if (static_cast<long>(fine_->grid().cells()) >= parallel_min_cells)
  for (int l = 0; l < ny * nz; ++l) {
    const int J = l % ny, K = l / ny;
    const auto& ly = restr_[1][static_cast<std::size_t>(J)];
    const auto& lz = restr_[2][static_cast<std::size_t>(K)];
    for (int I = 0; I < nx; ++I) {
      double v = 0;
      if (coarse_->active(I, J, K)) {
        const auto& lx = restr_[0][static_cast<std::size_t>(I)];
        for (const auto& [k, wz] : lz)
          for (const auto& [j, wy] : ly) {
            const double* r = &fr(0, j, k);
            const double* s = sc ? sc + static_cast<std::size_t>(fnx) * (static_cast<std::size_t>(j) +
                                                                         static_cast<std::size_t>(fny) * k)
                                 : nullptr;
            double vx = 0;
            for (const auto& [i, wx] : lx) vx += wx * (s ? s[i] * r[i] : r[i]);
            v += wz * wy * vx;
          }
      }
      cb(I, J, K) = v;
    }
  }
}

}  // namespace finverse::cfd
