// Ghost layers across rank boundaries (issue 48, deliverable 2; docs/studies/flow_mpi.md).
//
// A rank's Field holds its block's lines (block_decomposition.hpp) with `ghost` layers around.
// exchange() fills the ghost layers that face another rank's block, including a periodic wrap in
// y or z, from that rank's interior: first across y over the block's own z extent, then across
// z over the y extent widened by the y ghosts just received, so edge and corner ghosts arrive in
// the second pass (the two-pass order of structured-grid codes; no diagonal messages). All of x
// travels, x ghosts included: whole x lines are rank-local, so a periodic x wrap is the caller's
// and done before the exchange. Ghosts on the domain's own walls are left as they were (the
// boundary conditions own them).
#pragma once

#include <mpi.h>

#include <array>
#include <cstddef>
#include <vector>

#include "cfd/grid/field.hpp"
#include "cfd/parallel/block_decomposition.hpp"

namespace finverse::cfd {

class HaloExchange {
 public:
  HaloExchange(MPI_Comm comm, const BlockDecomposition& decomposition, const std::array<bool, 3>& periodic);

  // Fills `local`'s ghost layers that face other blocks. `local` must be shaped nx x block.ny x
  // block.nz (any ghost width); every rank of the communicator calls it.
  void exchange(Field& local) const;
  // Doubles this rank received in its last exchange, and in all since construction.
  std::size_t received_last() const { return received_; }
  std::size_t received_total() const { return total_; }
  long exchanges() const { return exchanges_; }

 private:
  void pass(Field& f, int axis) const;

  MPI_Comm comm_;
  int rank_ = 0;
  BlockDecomposition d_;
  std::array<bool, 3> periodic_{};
  mutable std::vector<double> send_, recv_;
  mutable std::size_t received_ = 0, total_ = 0;
  mutable long exchanges_ = 0;
};

}  // namespace finverse::cfd
