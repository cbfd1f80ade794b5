// Connected components of the pressure operator across MPI ranks; see distributed_components.hpp.
#include "cfd/parallel/distributed_components.hpp"

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace finverse::cfd {

DistributedComponents::DistributedComponents(const DistributedPoisson& dp) {
  const PoissonOperator& op = dp.block_operator();
  const DistributedGrid& g = dp.grid();
  const BoundaryConditions& bc = dp.bc_whole();
  const StretchedGrid& grid = op.grid();
  const Block& b = g.block();
  const int nx = grid.nx(), ny = grid.ny(), nz = grid.nz(), dim = grid.dim();
  const int NY = g.decomposition().ny(), NZ = g.decomposition().nz();
  nx_ = nx, ny_ = ny;
  const std::size_t cells = grid.cells();
  const FaceCoefficients& beta = op.beta();
  const auto open = [&](int d, int i, int j, int k) { return op.transmissibility(d)[beta.index(d, i, j, k)] > 0; };

  // 1. The block's own union-find (x wraps locally; y and z sides wait for the exchange).
  std::vector<std::size_t> parent(cells);
  for (std::size_t c = 0; c < cells; ++c) parent[c] = c;
  const auto find = [&](std::size_t c) {
    while (parent[c] != c) c = parent[c] = parent[parent[c]];
    return c;
  };
  const auto join = [&](std::size_t a, std::size_t c) {
    a = find(a), c = find(c);
    if (a != c) parent[std::max(a, c)] = std::min(a, c);
  };
  std::vector<char> pinned(cells, 0);
  const int n[3] = {nx, ny, nz}, lo[3] = {0, b.j0, b.k0}, whole_n[3] = {nx, NY, NZ};
  const std::size_t stride[3] = {1, static_cast<std::size_t>(nx), static_cast<std::size_t>(nx) * ny};
  for (int d = 0; d < dim; ++d)
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          const int m = d == 0 ? i : d == 1 ? j : k;
          const std::size_t c = op.cell_index(i, j, k);
          const bool low_domain = m + lo[d] == 0, high_domain = m + lo[d] == whole_n[d] - 1;
          if (open(d, i, j, k)) {
            if (m > 0) join(c, c - stride[d]);
            else if (d == 0 && bc.periodic(0)) join(c, c + static_cast<std::size_t>(n[0] - 1));
            else if (low_domain && !bc.periodic(d)) pinned[c] = 1;  // a Dirichlet face of the domain
          }
          if (m == n[d] - 1 && high_domain && !bc.periodic(d)) {
            int f[3] = {i, j, k};
            ++f[d];
            if (open(d, f[0], f[1], f[2])) pinned[c] = 1;
          }
        }
  // 2. Labels: each local set's smallest global cell index, and its pin.
  constexpr double none = std::numeric_limits<double>::infinity();
  std::vector<double> label(cells, none);
  std::vector<char> pin(cells, 0);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const std::size_t c = op.cell_index(i, j, k);
        if (!op.active(i, j, k)) continue;
        const std::size_t r = find(c);
        const double global = static_cast<double>(i) + nx * (static_cast<double>(j + b.j0) + NY * static_cast<double>(k + b.k0));
        label[r] = std::min(label[r], global);
        pin[r] = static_cast<char>(pin[r] | pinned[c]);
      }
  // 3. Across the block sides until nothing changes.
  Field L = g.make_field(1), P = g.make_field(1);
  for (;;) {
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          const std::size_t r = find(op.cell_index(i, j, k));
          L(i, j, k) = op.active(i, j, k) ? label[r] : none;
          P(i, j, k) = pin[r];
        }
    g.exchange(L);
    g.exchange(P);
    int changed = 0;
    for (int d = 1; d < dim; ++d)
      for (int side : {0, 1}) {
        if (g.decomposition().neighbour(g.rank(), d, side ? 1 : -1, g.periodic()) < 0) continue;
        const int m = side ? n[d] - 1 : 0, ghost = side ? n[d] : -1;
        for (int q = 0; q < (d == 1 ? nz : ny); ++q)
          for (int i = 0; i < nx; ++i) {
            const int j = d == 1 ? m : q, k = d == 2 ? m : q;
            const int f[3] = {i, d == 1 ? m + side : j, d == 2 ? m + side : k};
            if (!op.active(i, j, k) || !open(d, f[0], f[1], f[2])) continue;
            const double gl = d == 1 ? L(i, ghost, k) : L(i, j, ghost);
            const double gp = d == 1 ? P(i, ghost, k) : P(i, j, ghost);
            const std::size_t r = find(op.cell_index(i, j, k));
            if (gl < label[r]) label[r] = gl, changed = 1;
            if (gp > 0 && !pin[r]) pin[r] = 1, changed = 1;
          }
      }
    ++rounds_;
    MPI_Allreduce(MPI_IN_PLACE, &changed, 1, MPI_INT, MPI_MAX, g.communicator());
    if (!changed) break;
  }
  // 4. Global ids in label order; a component is singular unless some rank saw it pinned.
  std::vector<double> mine;
  for (std::size_t c = 0; c < cells; ++c)
    if (find(c) == c && label[c] != none) mine.push_back(pin[c] ? -label[c] - 1 : label[c]);
  int count = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(g.size())), displs(static_cast<std::size_t>(g.size()));
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, g.communicator());
  int total = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) displs[r] = total, total += counts[r];
  std::vector<double> all(static_cast<std::size_t>(total));
  MPI_Allgatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE, g.communicator());
  std::vector<std::pair<double, char>> entries;  // (label, pinned)
  for (double v : all) entries.emplace_back(v < 0 ? -v - 1 : v, v < 0 ? 1 : 0);
  std::sort(entries.begin(), entries.end());
  std::vector<double> labels;
  for (const auto& [l, p] : entries) {
    if (labels.empty() || labels.back() != l) labels.push_back(l), singular_.push_back(1);
    if (p) singular_.back() = 0;
  }
  id_.assign(cells, -1);
  for (std::size_t c = 0; c < cells; ++c) {
    const double l = label[find(c)];
    if (l == none || !(op.diagonal()[c] > 0)) continue;
    id_[c] = static_cast<int>(std::lower_bound(labels.begin(), labels.end(), l) - labels.begin());
  }
}

int DistributedComponents::component(int i, int j, int k) const {
  return id_[static_cast<std::size_t>(i) + static_cast<std::size_t>(nx_) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(ny_) * k)];
}

bool DistributedComponents::any_singular() const {
  return std::any_of(singular_.begin(), singular_.end(), [](char s) { return s != 0; });
}

}  // namespace finverse::cfd
