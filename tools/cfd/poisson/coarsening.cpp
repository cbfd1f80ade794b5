// Isotropy-targeting multigrid coarsening on stretched grids; see coarsening.hpp.
#include "cfd/poisson/coarsening.hpp"

#include <algorithm>
#include <limits>

namespace finverse::cfd {

AxisCoarsening AxisCoarsening::identity(int n) {
  AxisCoarsening a;
  for (int i = 0; i <= n; ++i) a.first.push_back(i);
  for (int i = 0; i < n; ++i) a.parent.push_back(i);
  return a;
}

AxisCoarsening AxisCoarsening::pairs(const std::vector<bool>& merge) {
  AxisCoarsening a;
  const int n = static_cast<int>(merge.size());
  int i = 0;
  while (i < n) {
    const int c = static_cast<int>(a.first.size());  // index of the coarse cell begun here
    a.first.push_back(i);
    const int kids = i + 1 < n && merge[static_cast<std::size_t>(i)] ? 2 : 1;
    for (int q = 0; q < kids; ++q) a.parent.push_back(c);
    i += kids;
  }
  a.first.push_back(n);
  return a;
}

namespace {
// Pairs within each run of consecutive cells no wider than `limit`. A run of odd length keeps one
// cell single: the widest of those whose removal leaves even parts on both sides. Leaving always
// the run's last cell single instead (plain left-to-right pairing) keeps that cell, often a wall
// cell, at its fine width level after level; being the narrowest cell of the level it then caps
// h_min and with it the coarsening of the whole grid (measured: docs/studies/poisson_multigrid.md).
std::vector<bool> pair_runs(const Axis& ax, double limit) {
  const int n = ax.size();
  std::vector<bool> merge(static_cast<std::size_t>(n), false);
  int s = 0;
  while (s < n) {
    if (!(ax.width(s) <= limit)) {
      ++s;
      continue;
    }
    int e = s;  // the run is s .. e
    while (e + 1 < n && ax.width(e + 1) <= limit) ++e;
    const int len = e - s + 1;
    int single = -1;
    if (len % 2 == 1) {
      single = s;
      for (int i = s + 2; i <= e; i += 2)
        if (ax.width(i) > ax.width(single)) single = i;
    }
    for (int i = s; i < e;) {
      if (i == single) {
        ++i;
        continue;
      }
      merge[static_cast<std::size_t>(i)] = true;
      i += 2;
    }
    s = e + 1;
  }
  return merge;
}
}  // namespace

Coarsening choose_coarsening(const PoissonOperator& op, double ratio) { return choose_coarsening(op.grid(), op.bc(), ratio); }

Coarsening choose_coarsening(const StretchedGrid& g, const BoundaryConditions& bc, double ratio) {
  double hmin = std::numeric_limits<double>::infinity();
  for (int d = 0; d < g.dim(); ++d) hmin = std::min(hmin, g.axis(d).min_width());
  const double limit = ratio > 0 ? ratio * hmin * (1 + 1e-12) : std::numeric_limits<double>::infinity();
  Coarsening c;
  for (int d = 0; d < 3; ++d) {
    const Axis& ax = g.axis(d);
    const int n = ax.size();
    auto& cd = c[static_cast<std::size_t>(d)];
    cd = AxisCoarsening::identity(n);
    if (d >= g.dim() || n < 3) continue;
    if (bc.periodic(d)) {
      if (n % 4 == 0 && ax.max_width() <= limit)
        cd = AxisCoarsening::pairs(std::vector<bool>(static_cast<std::size_t>(n), true));
      continue;
    }
    cd = AxisCoarsening::pairs(pair_runs(ax, limit));
  }
  return c;
}

bool coarsens(const Coarsening& c) { return c[0].merges() || c[1].merges() || c[2].merges(); }

StretchedGrid coarsen_grid(const StretchedGrid& fine, const Coarsening& c) {
  auto axis = [&](int d) {
    const Axis& a = fine.axis(d);
    std::vector<double> f;
    for (int i : c[static_cast<std::size_t>(d)].first) f.push_back(a.face(i));
    return Axis(std::move(f));
  };
  if (fine.dim() == 2) return StretchedGrid(axis(0), axis(1));
  return StretchedGrid(axis(0), axis(1), axis(2));
}

FaceCoefficients coarsen_beta(const StretchedGrid& g, const FaceCoefficients& beta, const Coarsening& c,
                              const StretchedGrid& cg) {
  FaceCoefficients cb(cg, 0.0);
  for (int d = 0; d < g.dim(); ++d) {
    const int e[3] = {cg.nx() + (d == 0), cg.ny() + (d == 1), cg.nz() + (d == 2)};
    // Each coarse face is written once, so its lines run in parallel (every step of a moving body).
#pragma omp parallel for schedule(static) if (static_cast<long>(g.cells()) >= parallel_min_cells)
    for (int L = 0; L < e[1] * e[2]; ++L) {
      const int J = L % e[1], K = L / e[1];
      for (int I = 0; I < e[0]; ++I) {
        // Fine faces covering coarse face (I,J,K): along d the coinciding fine face, tangentially
        // the children of the coarse cell.
        const int C[3] = {I, J, K};
        int lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
          const auto& m = c[static_cast<std::size_t>(a)];
          const auto ca = static_cast<std::size_t>(C[a]);
          if (a == d)
            lo[a] = hi[a] = m.first[ca];
          else
            lo[a] = m.first[ca], hi[a] = m.first[ca + 1] - 1;
        }
        double num = 0, den = 0;
        for (int k = lo[2]; k <= hi[2]; ++k)
          for (int j = lo[1]; j <= hi[1]; ++j)
            for (int i = lo[0]; i <= hi[0]; ++i) {
              const double a = g.face_area(d, i, j, k);
              num += a * beta(d, i, j, k);
              den += a;
            }
        cb(d, I, J, K) = num / den;
      }
    }
  }
  return cb;
}

PoissonOperator coarsen_operator(const PoissonOperator& fine, const Coarsening& c) {
  const StretchedGrid cg = coarsen_grid(fine.grid(), c);
  PoissonOperator coarse;
  coarse.setup(cg, coarsen_beta(fine.grid(), fine.beta(), c, cg), fine.bc());
  return coarse;
}

}  // namespace finverse::cfd
