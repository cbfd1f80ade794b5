// Ghost-layer exchange between the ranks' blocks; see halo_exchange.hpp.
#include "cfd/parallel/halo_exchange.hpp"

#include <string>

#include "core/error.hpp"

namespace finverse::cfd {

HaloExchange::HaloExchange(MPI_Comm comm, const BlockDecomposition& decomposition, const std::array<bool, 3>& periodic)
    : comm_(comm), d_(decomposition), periodic_(periodic) {
  int size = 0;
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size);
  if (size != d_.ranks())
    throw Error("halo exchange: the decomposition has " + std::to_string(d_.ranks()) + " blocks for " + std::to_string(size) +
                " ranks");
}

void HaloExchange::exchange(Field& f) const {
  const Block& b = d_.block(rank_);
  if (f.nx() != d_.nx() || f.ny() != b.ny() || f.nz() != b.nz())
    throw Error("halo exchange: rank " + std::to_string(rank_) + "'s field is " + std::to_string(f.nx()) + " x " +
                std::to_string(f.ny()) + " x " + std::to_string(f.nz()) + ", its block " + std::to_string(d_.nx()) + " x " +
                std::to_string(b.ny()) + " x " + std::to_string(b.nz()));
  received_ = 0;
  ++exchanges_;
  if (f.ghost() == 0) return;
  if (f.ghost() > b.ny() || (d_.dim() == 3 && f.ghost() > b.nz()))
    throw Error("halo exchange: " + std::to_string(f.ghost()) + " ghost layers are deeper than rank " + std::to_string(rank_) +
                "'s block of " + std::to_string(b.ny()) + " x " + std::to_string(b.nz()) + " lines");
  pass(f, 1);
  if (d_.dim() == 3) pass(f, 2);
  total_ += received_;
}

// One axis: the layers next to each face go to the neighbour on that side, and its layers come
// back into this side's ghosts. Sendrecv pairs (send up / receive from below, then the reverse)
// cannot deadlock, and MPI_PROC_NULL makes a wall side a no-op.
void HaloExchange::pass(Field& f, int axis) const {
  const int g = f.ghost();
  const int gz = f.dim() == 3 ? g : 0;
  const int i0 = -g, i1 = f.nx() + g;
  // The slab: layers [l0, l0 + g) along `axis`, across the other two the full extent (y ghosts
  // included on the z pass).
  const int j_lo = axis == 2 ? -g : 0, j_hi = axis == 2 ? f.ny() + g : f.ny();
  const int k_lo = axis == 1 ? 0 : -gz, k_hi = axis == 1 ? f.nz() : f.nz() + gz;
  const int n = axis == 1 ? f.ny() : f.nz();
  const auto slab = [&](int l0, auto&& visit) {
    for (int k = axis == 2 ? l0 : k_lo; k < (axis == 2 ? l0 + g : k_hi); ++k)
      for (int j = axis == 1 ? l0 : j_lo; j < (axis == 1 ? l0 + g : j_hi); ++j)
        for (int i = i0; i < i1; ++i) visit(f(i, j, k));
  };
  const std::size_t count = static_cast<std::size_t>(g) * static_cast<std::size_t>(i1 - i0) *
                            static_cast<std::size_t>(axis == 1 ? k_hi - k_lo : j_hi - j_lo);
  send_.resize(count), recv_.resize(count);
  for (int side : {+1, -1}) {
    const int to = d_.neighbour(rank_, axis, side, periodic_);
    const int from = d_.neighbour(rank_, axis, -side, periodic_);
    std::size_t c = 0;
    if (to >= 0) slab(side > 0 ? n - g : 0, [&](double& v) { send_[c++] = v; });
    MPI_Sendrecv(send_.data(), to >= 0 ? static_cast<int>(count) : 0, MPI_DOUBLE, to >= 0 ? to : MPI_PROC_NULL, 10 * axis + (side > 0),
                 recv_.data(), from >= 0 ? static_cast<int>(count) : 0, MPI_DOUBLE, from >= 0 ? from : MPI_PROC_NULL,
                 10 * axis + (side > 0), comm_, MPI_STATUS_IGNORE);
    if (from < 0) continue;
    c = 0;
    slab(side > 0 ? -g : n, [&](double& v) { v = recv_[c++]; });
    received_ += count;
  }
}

}  // namespace finverse::cfd
