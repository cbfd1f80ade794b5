// Pencil decomposition of the flow grid over ranks; see block_decomposition.hpp.
#include "cfd/parallel/block_decomposition.hpp"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <string>

#include "core/error.hpp"

namespace finverse::cfd {
namespace {

// Edges of p nearly equal parts of n: the first n mod p parts one longer.
std::vector<int> split(int n, int p) {
  std::vector<int> e(static_cast<std::size_t>(p) + 1, 0);
  for (int b = 0; b < p; ++b) e[static_cast<std::size_t>(b) + 1] = e[static_cast<std::size_t>(b)] + n / p + (b < n % p ? 1 : 0);
  return e;
}

// The best py for `ranks`, or 0 when no factorisation gives min_lines per block.
int best_py(int ny, int nz, int dim, int ranks, int min_lines) {
  int best = 0;
  double best_perimeter = std::numeric_limits<double>::infinity();
  for (int py = ranks; py >= 1; --py) {
    if (ranks % py) continue;
    const int pz = ranks / py;
    if (dim == 2 && pz != 1) continue;
    if (ny / py < min_lines && py > 1) continue;
    if (nz / pz < min_lines && pz > 1) continue;
    if (py > ny || pz > nz) continue;
    // The largest block's halo: its two y faces span its z extent and vice versa.
    const double by = (ny + py - 1) / py, bz = (nz + pz - 1) / pz;
    const double perimeter = (py > 1 ? 2 * bz : 0) + (pz > 1 ? 2 * by : 0);
    if (perimeter < best_perimeter) best_perimeter = perimeter, best = py;
  }
  return best;
}

}  // namespace

int BlockDecomposition::largest_feasible(int ny, int nz, int dim, int ranks, int min_lines) {
  for (int r = ranks; r > 1; --r)
    if (best_py(ny, nz, dim, r, min_lines) > 0) return r;
  return 1;
}

BlockDecomposition::BlockDecomposition(int nx, int ny, int nz, int dim, int ranks, int min_lines)
    : nx_(nx), ny_(ny), nz_(nz), dim_(dim) {
  if (nx < 1 || ny < 1 || nz < 1 || (dim != 2 && dim != 3) || (dim == 2 && nz != 1))
    throw Error("block decomposition: bad grid " + std::to_string(nx) + " x " + std::to_string(ny) + " x " +
                std::to_string(nz) + " in " + std::to_string(dim) + "-D");
  if (ranks < 1) throw Error("block decomposition: expected at least one rank, got " + std::to_string(ranks));
  py_ = best_py(ny, nz, dim, ranks, min_lines);
  if (py_ == 0)
    throw Error("the flow grid's " + std::to_string(ny) + " x " + std::to_string(nz) + " lines (y x z) cannot be split into " +
                std::to_string(ranks) + " ranks with at least " + std::to_string(min_lines) +
                " lines per rank in each cut direction: use at most " +
                std::to_string(largest_feasible(ny, nz, dim, ranks, min_lines)) + " ranks, or a rank count with other factors");
  pz_ = ranks / py_;
  ys_ = split(ny, py_), zs_ = split(nz, pz_);
  make_blocks();
}

BlockDecomposition::BlockDecomposition(int nx, int ny, int nz, int dim, std::vector<int> y_edges, std::vector<int> z_edges)
    : nx_(nx), ny_(ny), nz_(nz), dim_(dim), ys_(std::move(y_edges)), zs_(std::move(z_edges)) {
  const auto valid = [](const std::vector<int>& e, int n) {
    if (e.size() < 2 || e.front() != 0 || e.back() != n) return false;
    for (std::size_t b = 1; b < e.size(); ++b)
      if (e[b] <= e[b - 1]) return false;
    return true;
  };
  if (!valid(ys_, ny) || !valid(zs_, nz) || (dim == 2 && zs_.size() != 2))
    throw Error("block decomposition: block edges must rise strictly from 0 to the line count (" + std::to_string(ny) + " x " +
                std::to_string(nz) + ")");
  py_ = static_cast<int>(ys_.size()) - 1, pz_ = static_cast<int>(zs_.size()) - 1;
  make_blocks();
}

void BlockDecomposition::make_blocks() {
  blocks_.resize(static_cast<std::size_t>(py_ * pz_));
  for (int r = 0; r < py_ * pz_; ++r) {
    const auto a = static_cast<std::size_t>(r % py_), b = static_cast<std::size_t>(r / py_);
    blocks_[static_cast<std::size_t>(r)] = Block{ys_[a], ys_[a + 1], zs_[b], zs_[b + 1]};
  }
}

BlockDecomposition BlockDecomposition::snapped(const std::vector<int>& y_allowed, const std::vector<int>& z_allowed,
                                               int min_lines) const {
  const auto snap = [&](const std::vector<int>& edges, const std::vector<int>& allowed, int n, const char* axis) {
    std::vector<int> out{0};
    for (std::size_t b = 1; b + 1 < edges.size(); ++b) {
      int best = -1;
      for (int a : allowed)
        if (a >= out.back() + min_lines && a <= n - min_lines && (best < 0 || std::abs(a - edges[b]) < std::abs(best - edges[b])))
          best = a;
      if (best < 0)
        throw Error(std::string("block decomposition: no coarse face along ") + axis + " leaves " + std::to_string(min_lines) +
                    " lines per block for " + std::to_string(edges.size() - 1) + " blocks; use fewer ranks");
      out.push_back(best);
    }
    out.push_back(n);
    if (out.size() > 2 && out[out.size() - 1] - out[out.size() - 2] < min_lines)
      throw Error(std::string("block decomposition: the last block along ") + axis + " gets fewer than " +
                  std::to_string(min_lines) + " lines on the coarse faces; use fewer ranks");
    return out;
  };
  return BlockDecomposition(nx_, ny_, nz_, dim_, snap(ys_, y_allowed, ny_, "y"), pz_ > 1 ? snap(zs_, z_allowed, nz_, "z") : zs_);
}

BlockDecomposition BlockDecomposition::coarsened(int coarse_nx, const std::vector<int>& y_parent,
                                                 const std::vector<int>& z_parent) const {
  const auto map = [](const std::vector<int>& edges, const std::vector<int>& parent, const char* axis) {
    std::vector<int> out;
    const int nc = parent.empty() ? 0 : parent.back() + 1;
    for (int e : edges) {
      const auto ue = static_cast<std::size_t>(e);
      if (e > 0 && ue < parent.size() && parent[ue - 1] == parent[ue])
        throw Error(std::string("block decomposition: a block edge along ") + axis + " splits a coarse cell");
      out.push_back(ue < parent.size() ? parent[ue] : nc);
    }
    return out;
  };
  return BlockDecomposition(coarse_nx, y_parent.back() + 1, z_parent.back() + 1, dim_, map(ys_, y_parent, "y"),
                            map(zs_, z_parent, "z"));
}

int BlockDecomposition::neighbour(int rank, int axis, int side, const std::array<bool, 3>& periodic) const {
  if (axis != 1 && axis != 2) throw Error("block decomposition: neighbours are across y (1) or z (2), not axis " + std::to_string(axis));
  int a = rank % py_, b = rank / py_;
  int& c = axis == 1 ? a : b;
  const int p = axis == 1 ? py_ : pz_;
  c += side;
  if (c < 0 || c >= p) {
    if (!periodic[static_cast<std::size_t>(axis)] || (axis == 2 && dim_ == 2)) return -1;
    c = (c + p) % p;
  }
  return a + py_ * b;
}

int BlockDecomposition::owner(int j, int k) const {
  const int a = static_cast<int>(std::upper_bound(ys_.begin(), ys_.end(), j) - ys_.begin()) - 1;
  const int b = static_cast<int>(std::upper_bound(zs_.begin(), zs_.end(), k) - zs_.begin()) - 1;
  return a + py_ * b;
}

std::size_t BlockDecomposition::max_halo_cells(int ghost, const std::array<bool, 3>& periodic) const {
  std::size_t most = 0;
  const int gz = dim_ == 3 ? ghost : 0;
  for (int r = 0; r < ranks(); ++r) {
    const Block& b = block(r);
    const bool ylo = neighbour(r, 1, -1, periodic) >= 0, yhi = neighbour(r, 1, 1, periodic) >= 0;
    const bool zlo = dim_ == 3 && neighbour(r, 2, -1, periodic) >= 0, zhi = dim_ == 3 && neighbour(r, 2, 1, periodic) >= 0;
    // y faces over the block's z extent, then z faces over the y extent widened by the y ghosts
    // that were received (the exchange's order: edges and corners ride along).
    const std::size_t wy = static_cast<std::size_t>(b.ny() + ghost * (ylo + yhi));
    std::size_t cells = static_cast<std::size_t>(ghost) * static_cast<std::size_t>(b.nz()) * (ylo + yhi) +
                        static_cast<std::size_t>(gz) * wy * (zlo + zhi);
    cells *= static_cast<std::size_t>(nx_ + 2 * ghost);
    most = std::max(most, cells);
  }
  return most;
}

}  // namespace finverse::cfd
