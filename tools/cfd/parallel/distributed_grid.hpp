// The flow grid spread over MPI ranks: each rank's block, its fields, the halo exchange, global
// reductions and the gather/scatter of whole fields (issue 48, deliverable 2;
// docs/studies/flow_mpi.md).
//
// Reductions are bitwise those of the serial field.hpp on the whole grid, for any rank count:
// field.hpp sums each x line (lane_sum) and then the lines in the order l = j + ny k. Lines are
// whole on one rank (pencils), so every rank computes its lines' sums exactly as the serial code
// does, the sums are gathered onto every rank in rank order, and each rank adds them in the
// global line order. The price is ny x nz doubles per reduction (a 2-D array of line sums, not
// the 3-D field); the gain is that a run's iterates, residuals and outputs do not depend on the
// rank count. Files are written from the gathered field, so they do not either.
#pragma once

#include <mpi.h>

#include <array>
#include <cstddef>
#include <vector>

#include "cfd/grid/field.hpp"
#include "cfd/parallel/block_decomposition.hpp"
#include "cfd/parallel/halo_exchange.hpp"

namespace finverse::cfd {

class DistributedGrid {
 public:
  // Collective. Throws (block_decomposition.hpp) when the grid cannot be split into the
  // communicator's ranks.
  DistributedGrid(MPI_Comm comm, int nx, int ny, int nz, int dim, const std::array<bool, 3>& periodic, int min_lines = 2);
  // Collective; a given split (one block per rank of comm).
  DistributedGrid(MPI_Comm comm, const BlockDecomposition& decomposition, const std::array<bool, 3>& periodic);

  int rank() const { return rank_; }
  int size() const { return d_.ranks(); }
  MPI_Comm communicator() const { return comm_; }
  const std::array<bool, 3>& periodic() const { return periodic_; }
  const BlockDecomposition& decomposition() const { return d_; }
  const Block& block() const { return d_.block(rank_); }
  // This rank's part of a field: nx x block.ny x block.nz with `ghost` layers.
  Field make_field(int ghost = 1) const;

  // Collective: ghost layers facing other blocks (halo_exchange.hpp).
  void exchange(Field& local) const { halo_.exchange(local); }
  std::size_t halo_doubles_last() const { return halo_.received_last(); }
  // Since construction: doubles this rank received in halo exchanges, exchanges, and reductions
  // (each gathers the whole grid's ny x nz line sums).
  std::size_t halo_doubles_total() const { return halo_.received_total(); }
  long exchanges() const { return halo_.exchanges(); }
  long reductions() const { return reductions_; }

  // Collective reductions over the whole grid's interior, bitwise field.hpp's on the whole field.
  double dot(const Field& a, const Field& b) const;
  double norm2(const Field& a) const;
  double max_abs(const Field& a) const;
  // Collective: sum over the whole grid's lines of line(j, k) (this rank's lines, local indices),
  // added in the global line order l = j + ny k, as field.hpp's ordered_line_sum does.
  template <class LineSum>
  double line_sum(const Field& shape, LineSum line) const;

  // Collective. gather: the whole grid's interior onto `root` (global must be shaped nx x ny x nz
  // there; ignored elsewhere). scatter: the reverse, every rank's interior from root's field.
  void gather(const Field& local, Field& global, int root = 0) const;
  void scatter(const Field& global, Field& local, int root = 0) const;
  // Collective: the whole grid's interior onto every rank (a flow that every rank holds whole).
  void allgather(const Field& local, Field& global) const;
  // Not collective: this rank's block of a whole field that every rank holds.
  void own_part(const Field& global, Field& local) const;

 private:
  void index_lines();
  void pack_block(const Field& local, double* dst) const;
  void cell_counts(std::vector<int>& counts, std::vector<int>& displs) const;
  void unpack_whole(const double* all, Field& global) const;
  void check_whole(const Field& global, const char* what) const;

  MPI_Comm comm_;
  int rank_ = 0;
  std::array<bool, 3> periodic_;
  BlockDecomposition d_;
  HaloExchange halo_;
  std::vector<int> counts_, displs_;         // each rank's lines, and where they sit in the gathered array
  std::vector<std::size_t> line_position_;   // global line l -> its index in the gathered array
  mutable long reductions_ = 0;
  mutable std::vector<double> mine_, all_;  // line_sum's scratch
  mutable std::vector<double> cells_;       // gather's and allgather's scratch
};

template <class LineSum>
inline double DistributedGrid::line_sum(const Field& shape, LineSum line) const {
  // This rank's line sums, local line order (j fastest), as ordered_line_sum computes them.
  const int lines = shape.ny() * shape.nz();
  std::vector<double>& mine = mine_;  // scratch kept between calls: several reductions per iteration
  mine.resize(static_cast<std::size_t>(lines));
#pragma omp parallel for schedule(static) if (static_cast<long>(shape.nx()) * lines >= parallel_min_cells)
  for (int l = 0; l < lines; ++l) mine[static_cast<std::size_t>(l)] = line(l % shape.ny(), l / shape.ny());
  std::vector<double>& all = all_;
  all.resize(line_position_.size());
  ++reductions_;
  MPI_Allgatherv(mine.data(), lines, MPI_DOUBLE, all.data(), counts_.data(), displs_.data(), MPI_DOUBLE, comm_);
  double s = 0;
  for (std::size_t pos : line_position_) s += all[pos];
  return s;
}

}  // namespace finverse::cfd
