// The Poisson operator and red-black smoother over MPI ranks; see distributed_poisson.hpp.
#include "cfd/parallel/distributed_poisson.hpp"

#include <mpi.h>

#include <string>
#include <vector>

#include "core/error.hpp"
#include "cfd/poisson/smoother.hpp"

namespace finverse::cfd {
namespace {

// The last face along `axis` of a periodic axis takes face 0's beta (as the whole grid's
// operator does): the block holding face 0 sends that layer of faces to the block holding the
// last face (its neighbour below, across the wrap); with one block along the axis, a copy.
void wrap_periodic_beta(const DistributedGrid& g, FaceCoefficients& beta, int axis, const std::array<bool, 3>& periodic) {
  const Block& b = g.block();
  const int nx = g.decomposition().nx(), n_axis = axis == 1 ? g.decomposition().ny() : g.decomposition().nz();
  const int first = axis == 1 ? b.j0 : b.k0, last = axis == 1 ? b.j1 : b.k1;
  const int nb = axis == 1 ? b.ny() : b.nz();
  const int across = axis == 1 ? b.nz() : b.ny();  // the other cut direction's extent
  const auto face = [&](int layer, int i, int m) -> double& {
    return axis == 1 ? beta(1, i, layer, m) : beta(2, i, m, layer);
  };
  std::vector<double> send, recv(static_cast<std::size_t>(nx) * static_cast<std::size_t>(across));
  const int to = first == 0 ? g.decomposition().neighbour(g.rank(), axis, -1, periodic) : -1;
  const int from = last == n_axis ? g.decomposition().neighbour(g.rank(), axis, +1, periodic) : -1;
  if (to >= 0)
    for (int m = 0; m < across; ++m)
      for (int i = 0; i < nx; ++i) send.push_back(face(0, i, m));
  MPI_Sendrecv(send.data(), static_cast<int>(send.size()), MPI_DOUBLE, to >= 0 ? to : MPI_PROC_NULL, 40 + axis, recv.data(),
               from >= 0 ? static_cast<int>(recv.size()) : 0, MPI_DOUBLE, from >= 0 ? from : MPI_PROC_NULL, 40 + axis,
               g.communicator(), MPI_STATUS_IGNORE);
  if (from < 0) return;
  std::size_t c = 0;
  for (int m = 0; m < across; ++m)
    for (int i = 0; i < nx; ++i) face(nb, i, m) = recv[c++];
}

}  // namespace

FaceCoefficients block_faces(const FaceCoefficients& whole, const StretchedGrid& block_grid, const Block& b) {
  FaceCoefficients local(block_grid, 0.0);
  for (int d = 0; d < block_grid.dim(); ++d)
    for (int k = 0; k < block_grid.nz() + (d == 2); ++k)
      for (int j = 0; j < block_grid.ny() + (d == 1); ++j)
        for (int i = 0; i < block_grid.nx() + (d == 0); ++i) local(d, i, j, k) = whole(d, i, j + b.j0, k + b.k0);
  return local;
}

DistributedPoisson::DistributedPoisson(const DistributedGrid& grid, const StretchedGrid& whole, FaceCoefficients beta,
                                       const BoundaryConditions& bc)
    : grid_(grid), bc_(bc) {
  const auto& d = grid.decomposition();
  if (whole.nx() != d.nx() || whole.ny() != d.ny() || whole.nz() != d.nz())
    throw Error("distributed Poisson: the grid is " + std::to_string(whole.nx()) + " x " + std::to_string(whole.ny()) + " x " +
                std::to_string(whole.nz()) + " cells, its decomposition " + std::to_string(d.nx()) + " x " +
                std::to_string(d.ny()) + " x " + std::to_string(d.nz()));
  for (int axis : {1, 2})
    if (bc.periodic(axis) != grid.periodic()[static_cast<std::size_t>(axis)])
      throw Error("distributed Poisson: the boundary conditions and the halo exchange disagree on whether axis " +
                  std::to_string(axis) + " is periodic");
  const Block& b = grid.block();
  for (int axis = 1; axis < whole.dim(); ++axis)
    if (bc.periodic(axis)) wrap_periodic_beta(grid, beta, axis, grid.periodic());
  op_.setup_block(whole, beta, bc, b.j0, b.j1, b.k0, b.k1);
  parity_ = (b.j0 + b.k0) & 1;
  alone_ = grid.size() == 1 && !grid.periodic()[1] && !grid.periodic()[2];
}

void DistributedPoisson::refresh(Field& x) const {
  op_.fill_ghosts(x);  // a periodic x axis: lines are whole, the wrap is local
  grid_.exchange(x);
}

void DistributedPoisson::apply(Field& p, Field& out) const {
  refresh(p);
  op_.apply(p, out);  // its own fill_ghosts repeats the x wrap only
}

void DistributedPoisson::residual(const Field& b, Field& x, Field& r) const {
  refresh(x);
  op_.residual(b, x, r);
}

void DistributedPoisson::red_black_sweep(const Field& b, Field& x, bool forward, double omega) const {
  if (alone_) {
    cfd::red_black_sweep(op_, b, x, forward, omega);
    return;
  }
  for (int c : {0, 1}) {
    refresh(x);
    red_black_colour(op_, b, x, (forward ? c : 1 - c) ^ parity_, omega);
  }
}

void DistributedPoisson::red_black_sweep_residual(const Field& b, Field& x, double omega, Field& r) const {
  if (alone_) {
    cfd::red_black_sweep_residual(op_, b, x, omega, r);
    return;
  }
  red_black_sweep(b, x, true, omega);
  residual(b, x, r);
}

}  // namespace finverse::cfd
