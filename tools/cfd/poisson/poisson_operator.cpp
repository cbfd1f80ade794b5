// Finite-volume variable-coefficient Poisson operator on the stretched grid; see
// poisson_operator.hpp for the discretisation.
#include "cfd/poisson/poisson_operator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "cfd/grid/grid_loops.hpp"
#include "cfd/poisson/stencil_lines.hpp"

namespace finverse::cfd {

namespace {

// out = b - A p (with_b) or A p over the lines (j,k) of `range` in parallel (stencil_lines.hpp).
template <int D, bool WithB>
void stencil(const PoissonOperator& op, const Field* b, const Field& p, Field& out, const LineRange& range) {
  const StencilLines<D, WithB> lines(op, b, p, out);
  for_each_line(op.grid(), range, [&](int j, int k) { lines.line(j, k); });
}

}  // namespace

void PoissonOperator::setup(const StretchedGrid& grid, const FaceCoefficients& beta, const BoundaryConditions& bc,
                            Connectivity connectivity) {
  bc.validate();
  grid_ = grid;
  beta_ = beta;
  bc_ = bc;
  build(grid, bc, {0, 0, 0});
  if (connectivity == Connectivity::Build) build_connectivity();
}

void PoissonOperator::setup_block(const StretchedGrid& whole, const FaceCoefficients& beta, const BoundaryConditions& bc,
                                  int j0, int j1, int k0, int k1) {
  bc.validate();
  grid_ = whole.block(j0, j1, k0, k1);
  beta_ = beta;
  // Locally, a side inside the domain or on a periodic y/z axis is none of the operator's own
  // business: its ghosts come from the halo exchange. Neumann is the type that makes fill_ghosts
  // and assemble_rhs leave it alone; its transmissibilities come from the whole grid below.
  bc_ = bc;
  const int lo[3] = {0, j0, k0}, hi[3] = {whole.nx(), j1, k1}, n[3] = {whole.nx(), whole.ny(), whole.nz()};
  for (int d = 1; d < 3; ++d) {
    if (bc.periodic(d)) bc_[static_cast<Side>(2 * d)] = bc_[static_cast<Side>(2 * d + 1)] = BcType::Neumann;
    if (lo[d] > 0) bc_[static_cast<Side>(2 * d)] = BcType::Neumann;
    if (hi[d] < n[d]) bc_[static_cast<Side>(2 * d + 1)] = BcType::Neumann;
  }
  build(whole, bc, {0, j0, k0});
}

// Transmissibilities of the faces of grid_ (a block of `whole` at `offset`, or whole itself),
// each from whole's axes and bc exactly as for the whole grid, so that a block's coefficients are
// the whole grid's bit for bit. The last face of a periodic axis takes face 0's beta: from face 0
// itself where the block starts there, else from the block's own last face, which holds face 0's
// value (DistributedPoisson sends it there).
void PoissonOperator::build(const StretchedGrid& whole, const BoundaryConditions& bc, std::array<int, 3> offset) {
  const StretchedGrid& grid = grid_;
  const FaceCoefficients& beta = beta_;
  const int dim = grid.dim();
  const int n[3] = {grid.nx(), grid.ny(), grid.nz()};
  for (int d = 0; d < 3; ++d) {
    if (beta.faces(d) != static_cast<std::size_t>(n[0] + (d == 0)) * static_cast<std::size_t>(n[1] + (d == 1)) *
                             static_cast<std::size_t>(n[2] + (d == 2)))
      throw std::invalid_argument("PoissonOperator: face coefficients do not match the grid");
    const std::vector<double>& v = beta.values(d);
    const long count = static_cast<long>(v.size());
    bool bad = false;
#pragma omp parallel for schedule(static) reduction(|| : bad) if (count >= parallel_min_cells)
    for (long q = 0; q < count; ++q) {
      const double b = v[static_cast<std::size_t>(q)];
      bad = bad || !(b >= 0) || !std::isfinite(b);
    }
    if (bad) throw std::invalid_argument("PoissonOperator: beta must be finite and >= 0");
  }
  // The set-up runs on every multigrid level at every step of a moving body: its loops over faces
  // and cells run in parallel over lines (each writes only its own face or cell).
  const bool parallel = static_cast<long>(grid.cells()) >= parallel_min_cells;

  for (int d = 0; d < 3; ++d) {
    auto& t = t_[static_cast<std::size_t>(d)];
    t.assign(beta.faces(d), 0.0);
    if (d >= dim) continue;  // 2-D: no z faces
    const Axis& ax = whole.axis(d);
    const int nd = ax.size();
    const int od = offset[static_cast<std::size_t>(d)];
    const BcType lo = bc[static_cast<Side>(2 * d)], hi = bc[static_cast<Side>(2 * d + 1)];
    const int e[3] = {n[0] + (d == 0), n[1] + (d == 1), n[2] + (d == 2)};
#pragma omp parallel for schedule(static) if (parallel)
    for (int l = 0; l < e[1] * e[2]; ++l) {
      const int j = l % e[1], k = l / e[1];
      for (int i = 0; i < e[0]; ++i) {
        const int fl = d == 0 ? i : d == 1 ? j : k;  // face position along d, in the block
        const int f = fl + od;                        // ... and in the whole grid
        double dist;
        int bf = fl;  // face whose beta applies (a periodic last face takes face 0's)
        if (f > 0 && f < nd) dist = ax.centre_distance(f);
        else if (lo == BcType::Periodic) {
          dist = 0.5 * (ax.width(0) + ax.width(nd - 1));
          if (od == 0) bf = 0;  // the block holds face 0 itself; else its last face holds face 0's value
        } else if ((f == 0 ? lo : hi) == BcType::Dirichlet) dist = 0.5 * ax.width(f == 0 ? 0 : nd - 1);
        else continue;  // Neumann: the flux is data, it goes to the right-hand side
        int bi = i, bj = j, bk = k;
        (d == 0 ? bi : d == 1 ? bj : bk) = bf;
        t[beta.index(d, i, j, k)] = beta(d, bi, bj, bk) * whole.face_area(d, i + offset[0], j + offset[1], k + offset[2]) / dist;
      }
    }
  }

  diag_.assign(grid.cells(), 0.0);
  inv_diag_.assign(grid.cells(), 0.0);
  std::size_t active = 0;
#pragma omp parallel for schedule(static) reduction(+ : active) if (parallel)
  for (int l = 0; l < n[1] * n[2]; ++l) {
    const int j = l % n[1], k = l / n[1];
    for (int i = 0; i < n[0]; ++i) {
      double s = t_[0][beta.index(0, i, j, k)] + t_[0][beta.index(0, i + 1, j, k)] +
                 t_[1][beta.index(1, i, j, k)] + t_[1][beta.index(1, i, j + 1, k)];
      if (dim == 3) s += t_[2][beta.index(2, i, j, k)] + t_[2][beta.index(2, i, j, k + 1)];
      const std::size_t c = cell_index(i, j, k);
      diag_[c] = s;
      if (s > 0) {
        inv_diag_[c] = 1 / s;
        ++active;
      }
    }
  }
  active_cells_ = active;
  // Until build_connectivity runs (setup's default), the last set-up's components do not apply.
  connected_ = false;
  component_.clear();
  singular_.clear();
}

void PoissonOperator::fill_ghosts(Field& p) const {
  // Axis by axis, each pass also copying the ghosts written by the previous ones, so that edge and
  // corner ghosts are right too (linear prolongation reads them for doubly periodic domains).
  const int nx = grid_.nx(), ny = grid_.ny(), nz = grid_.nz();
  const int gz = dim() == 3 ? 1 : 0;
  if (bc_.periodic(0))
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j) p(-1, j, k) = p(nx - 1, j, k), p(nx, j, k) = p(0, j, k);
  if (bc_.periodic(1))
    for (int k = 0; k < nz; ++k)
      for (int i = -1; i <= nx; ++i) p(i, -1, k) = p(i, ny - 1, k), p(i, ny, k) = p(i, 0, k);
  if (gz && bc_.periodic(2))
    for (int j = -1; j <= ny; ++j)
      for (int i = -1; i <= nx; ++i) p(i, j, -1) = p(i, j, nz - 1), p(i, j, nz) = p(i, j, 0);
}

void PoissonOperator::apply(Field& p, Field& out, const LineRange& lines) const {
  fill_ghosts(p);
  if (dim() == 3) stencil<3, false>(*this, nullptr, p, out, lines);
  else stencil<2, false>(*this, nullptr, p, out, lines);
}

void PoissonOperator::residual(const Field& b, Field& x, Field& r) const {
  fill_ghosts(x);
  if (dim() == 3) stencil<3, true>(*this, &b, x, r, all_lines(grid_));
  else stencil<2, true>(*this, &b, x, r, all_lines(grid_));
}

void PoissonOperator::assemble_rhs(const Field& f, const BoundaryValues& values, Field& b,
                                   const LineRange& lines) const {
  const StretchedGrid& g = grid_;
  for_each_cell(g, lines,
                [&](int i, int j, int k) { b(i, j, k) = active(i, j, k) ? -f(i, j, k) * g.volume(i, j, k) : 0.0; });

  for (int s = 0; s < 2 * dim(); ++s) {
    const Side side = static_cast<Side>(s);
    const BcType type = bc_[side];
    const auto& v = values[side];
    if (type == BcType::Periodic || v.empty()) continue;
    if (v.size() != side_faces(g, side))
      throw std::invalid_argument("PoissonOperator::assemble_rhs: wrong number of boundary values");
    const int d = side_axis(side);
    const int cell = side_is_high(side) ? g.n(d) - 1 : 0;  // adjacent cell index along d
    const int face = side_is_high(side) ? g.n(d) : 0;
    const int na = d == 0 ? g.ny() : g.nx();                // first tangential extent
    const int nb = d == 2 ? g.ny() : g.nz();                // second tangential extent
    for (int q = 0; q < nb; ++q)
      for (int p = 0; p < na; ++p) {
        int ci[3], fi[3];
        const int t1 = d == 0 ? 1 : 0, t2 = d == 2 ? 1 : 2;
        ci[d] = cell, fi[d] = face;
        ci[t1] = fi[t1] = p;
        ci[t2] = fi[t2] = q;
        if (!lines.contains(ci[1], ci[2])) continue;
        const double val = v[static_cast<std::size_t>(p) + static_cast<std::size_t>(na) * q];
        const std::size_t fx = beta_.index(d, fi[0], fi[1], fi[2]);
        double add;
        if (type == BcType::Dirichlet) add = t_[static_cast<std::size_t>(d)][fx] * val;
        else add = beta_.values(d)[fx] * g.face_area(d, fi[0], fi[1], fi[2]) * val;
        b(ci[0], ci[1], ci[2]) += add;
      }
  }
}

// Components by union-find over the open faces in one scan (each cell joins its low-side
// neighbours), then labelled in scan order of their first active cell: the ids the flood fill of
// earlier versions gave, found about five times faster. This runs on every multigrid level at
// every step of a moving body (measured on the fin of the default case, 2.2 million cells: the
// flood fill took 9.5 % of the run).
void PoissonOperator::build_connectivity() {
  connected_ = true;
  const int nx = grid_.nx(), ny = grid_.ny(), nz = grid_.nz();
  component_.assign(grid_.cells(), -1);
  singular_.clear();
  if (single_open_component()) return;
  const std::size_t cells = grid_.cells();
  std::vector<std::size_t> parent(cells);
  for (std::size_t c = 0; c < cells; ++c) parent[c] = c;
  const auto find = [&](std::size_t c) {
    while (parent[c] != c) {
      parent[c] = parent[parent[c]];  // path halving
      c = parent[c];
    }
    return c;
  };
  const auto join = [&](std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  };
  // A non-periodic boundary face with nonzero transmissibility (a Dirichlet face) pins the
  // constant of its cell's component.
  std::vector<unsigned char> pins(cells, 0);
  const int n[3] = {nx, ny, nz};
  const std::size_t stride[3] = {1, static_cast<std::size_t>(nx), static_cast<std::size_t>(nx) * ny};
  for (int d = 0; d < dim(); ++d) {
    const auto& t = t_[static_cast<std::size_t>(d)];
    const bool periodic = bc_.periodic(d);
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          const int m = d == 0 ? i : d == 1 ? j : k;
          const std::size_t c = cell_index(i, j, k);
          if (t[beta_.index(d, i, j, k)] > 0) {  // the cell's low face
            if (m > 0) join(c, c - stride[d]);
            else if (periodic) join(c, c + static_cast<std::size_t>(n[d] - 1) * stride[d]);
            else pins[c] = 1;
          }
          if (m == n[d] - 1 && !periodic) {
            int f[3] = {i, j, k};
            ++f[d];
            if (t[beta_.index(d, f[0], f[1], f[2])] > 0) pins[c] = 1;
          }
        }
  }
  // Labels in scan order of each set's first active cell; cells joined to no active cell stay -1.
  std::vector<int> id_of_root(cells, -1);
  for (std::size_t c = 0; c < cells; ++c) {
    if (diag_[c] <= 0) continue;
    const std::size_t r = find(c);
    if (id_of_root[r] < 0) {
      id_of_root[r] = static_cast<int>(singular_.size());
      singular_.push_back(1);
    }
  }
  for (std::size_t c = 0; c < cells; ++c) {
    const int id = id_of_root[find(c)];
    component_[c] = id;
    if (id >= 0 && pins[c]) singular_[static_cast<std::size_t>(id)] = 0;
  }
}

// The common case without an immersed body: every cell active and every interior face open, so
// the grid is one component, pinned iff some non-periodic boundary face has T > 0 (only Dirichlet
// faces do). Saves the graph search on large grids; a face mask that closes any interior face
// (immersed body) takes the general path.
bool PoissonOperator::single_open_component() {
  if (active_cells_ != grid_.cells()) return false;
  const int n[3] = {grid_.nx(), grid_.ny(), grid_.nz()};
  bool pinned = false;
  for (int d = 0; d < dim(); ++d) {
    const auto& t = t_[static_cast<std::size_t>(d)];
    const int e[3] = {n[0] + (d == 0), n[1] + (d == 1), n[2] + (d == 2)};
    std::size_t f = 0;
    for (int k = 0; k < e[2]; ++k)
      for (int j = 0; j < e[1]; ++j)
        for (int i = 0; i < e[0]; ++i, ++f) {
          const int pos = d == 0 ? i : d == 1 ? j : k;
          const bool boundary = pos == 0 || pos == n[d];
          if (!boundary && !(t[f] > 0)) return false;
          if (boundary && !bc_.periodic(d) && t[f] > 0) pinned = true;
        }
  }
  component_.assign(grid_.cells(), 0);
  singular_.assign(1, pinned ? 0 : 1);
  return true;
}

void PoissonOperator::require_connectivity() const {
  if (!connected_)
    throw std::logic_error("PoissonOperator: set up without its connectivity (a block's, or a system solver's)");
}

bool PoissonOperator::any_singular() const {
  require_connectivity();
  for (char s : singular_)
    if (s) return true;
  return false;
}

namespace {
// Per-component sums of w(i,j,k) * x(i,j,k) and of w over the singular components, in a fixed
// order: each x line's cells in turn, then the line sums in line order (l = j + ny k). That is
// the order in which the ranks of a distributed solve add them (distributed_poisson_solver.cpp,
// line sums gathered in the global line order), so a run on MPI ranks projects the null space of
// an all-Neumann pressure with these bits, and its files equal one process's bit for bit.
template <class Weight>
void component_sums(const PoissonOperator& op, const Field& x, Weight w, std::vector<double>& sx,
                    std::vector<double>& sw) {
  const StretchedGrid& g = op.grid();
  sx.assign(static_cast<std::size_t>(op.components()), 0.0);
  sw.assign(static_cast<std::size_t>(op.components()), 0.0);
  const int* comp = op.component().data();
  // One pass; a line's partial sums per component, added to the totals when the line ends (a
  // component absent from a line adds nothing, so sealed pockets cost no extra pass).
  std::vector<double> lx(sx.size(), 0.0), lw(sw.size(), 0.0);
  std::vector<int> touched;
  for (int k = 0; k < g.nz(); ++k)
    for (int j = 0; j < g.ny(); ++j) {
      const int* line = comp + op.cell_index(0, j, k);
      for (int i = 0; i < g.nx(); ++i) {
        const int c = line[i];
        if (c < 0 || !op.singular(c)) continue;
        const auto u = static_cast<std::size_t>(c);
        if (lw[u] == 0 && std::find(touched.begin(), touched.end(), c) == touched.end()) touched.push_back(c);
        const double wi = w(i, j, k);
        lx[u] += wi * x(i, j, k);
        lw[u] += wi;
      }
      for (int c : touched) {
        const auto u = static_cast<std::size_t>(c);
        sx[u] += lx[u], sw[u] += lw[u];
        lx[u] = lw[u] = 0;
      }
      touched.clear();
    }
}

// x -= shift_c * w(i,j,k) on every singular component c.
template <class Weight>
void subtract(const PoissonOperator& op, Field& x, Weight w, const std::vector<double>& shift) {
  const StretchedGrid& g = op.grid();
  const auto& comp = op.component();
  for (int k = 0; k < g.nz(); ++k)
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) {
        const int c = comp[op.cell_index(i, j, k)];
        if (c >= 0 && op.singular(c)) x(i, j, k) -= shift[static_cast<std::size_t>(c)] * w(i, j, k);
      }
}
}  // namespace

void PoissonOperator::remove_mean(Field& r) const {
  if (!any_singular()) return;
  // Called twice per MG-PCG iteration, so the usual cases get a parallel, ordered sum and a
  // parallel shift: one singular component covering the grid (no immersed body), or one singular
  // component and inactive cells (a body: its cells carry component -1).
  if (components() == 1) {
    const int nx = grid_.nx(), ny = grid_.ny(), lines = grid_.ny() * grid_.nz();
    const bool all = active_cells_ == grid_.cells();
    const int* comp = component_.data();
    const double mean = ordered_line_sum(nx, ny, grid_.nz(), [&](int j, int k) {
                          const double* p = &r(0, j, k);
                          if (all) return lane_sum(nx, [&](int i) { return p[i]; });
                          const int* c = comp + cell_index(0, j, k);
                          return lane_sum(nx, [&](int i) { return c[i] == 0 ? p[i] : 0.0; });
                        }) /
                        static_cast<double>(active_cells_);
#pragma omp parallel for schedule(static) if (static_cast<long>(grid_.cells()) >= parallel_min_cells)
    for (int l = 0; l < lines; ++l) {
      double* p = &r(0, l % ny, l / ny);
      if (all) {
        for (int i = 0; i < nx; ++i) p[i] -= mean;
      } else {
        // Subtracting 0 leaves a value's bits as they are, and the select vectorises.
        const int* c = comp + cell_index(0, l % ny, l / ny);
        for (int i = 0; i < nx; ++i) p[i] -= c[i] == 0 ? mean : 0.0;
      }
    }
    return;
  }
  std::vector<double> s, n;
  auto one = [](int, int, int) { return 1.0; };
  component_sums(*this, r, one, s, n);
  for (std::size_t c = 0; c < s.size(); ++c) s[c] = n[c] > 0 ? s[c] / n[c] : 0;
  subtract(*this, r, one, s);
}

void PoissonOperator::make_compatible(Field& b) const {
  if (!any_singular()) return;
  std::vector<double> s, v;
  auto one = [](int, int, int) { return 1.0; };
  component_sums(*this, b, one, s, v);  // s = sum b
  auto vol = [&](int i, int j, int k) { return grid_.volume(i, j, k); };
  Field unit = make_field();
  unit.fill(1.0);
  std::vector<double> dummy;
  component_sums(*this, unit, vol, dummy, v);  // v = component volume
  for (std::size_t c = 0; c < s.size(); ++c) s[c] = v[c] > 0 ? s[c] / v[c] : 0;
  subtract(*this, b, vol, s);
}

void PoissonOperator::remove_volume_mean(Field& p) const {
  if (!any_singular()) return;
  std::vector<double> s, v;
  auto vol = [&](int i, int j, int k) { return grid_.volume(i, j, k); };
  component_sums(*this, p, vol, s, v);
  for (std::size_t c = 0; c < s.size(); ++c) s[c] = v[c] > 0 ? s[c] / v[c] : 0;
  subtract(*this, p, [](int, int, int) { return 1.0; }, s);
}

void PoissonOperator::zero_inactive(Field& x) const {
  if (active_cells_ == grid_.cells()) return;
  for (int k = 0; k < grid_.nz(); ++k)
    for (int j = 0; j < grid_.ny(); ++j)
      for (int i = 0; i < grid_.nx(); ++i)
        if (!active(i, j, k)) x(i, j, k) = 0;
}

}  // namespace finverse::cfd
