// The flow grid over MPI ranks: reductions and whole-field transfers; see distributed_grid.hpp.
#include "cfd/parallel/distributed_grid.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace finverse::cfd {
namespace {

int comm_size(MPI_Comm comm) {
  int size = 0;
  MPI_Comm_size(comm, &size);
  return size;
}

}  // namespace

DistributedGrid::DistributedGrid(MPI_Comm comm, int nx, int ny, int nz, int dim, const std::array<bool, 3>& periodic,
                                 int min_lines)
    : comm_(comm), periodic_(periodic), d_(nx, ny, nz, dim, comm_size(comm), min_lines), halo_(comm, d_, periodic) {
  index_lines();
}

DistributedGrid::DistributedGrid(MPI_Comm comm, const BlockDecomposition& decomposition, const std::array<bool, 3>& periodic)
    : comm_(comm), periodic_(periodic), d_(decomposition), halo_(comm, d_, periodic) {
  index_lines();
}

void DistributedGrid::index_lines() {
  const int ny = d_.ny(), nz = d_.nz();
  MPI_Comm_rank(comm_, &rank_);
  const int p = d_.ranks();
  counts_.resize(static_cast<std::size_t>(p)), displs_.resize(static_cast<std::size_t>(p));
  int offset = 0;
  for (int r = 0; r < p; ++r) {
    const Block& b = d_.block(r);
    counts_[static_cast<std::size_t>(r)] = b.ny() * b.nz(), displs_[static_cast<std::size_t>(r)] = offset;
    offset += b.ny() * b.nz();
  }
  line_position_.resize(static_cast<std::size_t>(ny) * static_cast<std::size_t>(nz));
  for (int r = 0; r < p; ++r) {
    const Block& b = d_.block(r);
    for (int k = b.k0; k < b.k1; ++k)
      for (int j = b.j0; j < b.j1; ++j)
        line_position_[static_cast<std::size_t>(j) + static_cast<std::size_t>(ny) * static_cast<std::size_t>(k)] =
            static_cast<std::size_t>(displs_[static_cast<std::size_t>(r)] + (j - b.j0) + b.ny() * (k - b.k0));
  }
}

Field DistributedGrid::make_field(int ghost) const { return Field(d_.nx(), block().ny(), block().nz(), d_.dim(), ghost); }

double DistributedGrid::dot(const Field& a, const Field& b) const {
  return line_sum(a, [&](int j, int k) {
    const double* pa = &a(0, j, k);
    const double* pb = &b(0, j, k);
    return lane_sum(a.nx(), [&](int i) { return pa[i] * pb[i]; });
  });
}

double DistributedGrid::norm2(const Field& a) const { return std::sqrt(dot(a, a)); }

double DistributedGrid::max_abs(const Field& a) const {
  double m = cfd::max_abs(a);  // max is exact: any order, any split gives the same bits
  MPI_Allreduce(MPI_IN_PLACE, &m, 1, MPI_DOUBLE, MPI_MAX, comm_);
  return m;
}

// gather and allgather: this rank's interior packed line by line, every rank's place in the
// gathered array (counts and offsets in doubles), and the gathered array unpacked into the whole
// field in rank order.
std::vector<double> DistributedGrid::packed_block(const Field& local) const {
  const Block& mine = block();
  std::vector<double> send(static_cast<std::size_t>(d_.nx()) * static_cast<std::size_t>(mine.ny() * mine.nz()));
  std::size_t c = 0;
  for (int k = 0; k < mine.nz(); ++k)
    for (int j = 0; j < mine.ny(); ++j)
      for (int i = 0; i < d_.nx(); ++i) send[c++] = local(i, j, k);
  return send;
}

void DistributedGrid::cell_counts(std::vector<int>& counts, std::vector<int>& displs) const {
  counts = counts_, displs = displs_;
  for (std::size_t r = 0; r < counts.size(); ++r) counts[r] *= d_.nx(), displs[r] *= d_.nx();
}

void DistributedGrid::unpack_whole(const std::vector<double>& all, Field& global, const char* what) const {
  if (global.nx() != d_.nx() || global.ny() != d_.ny() || global.nz() != d_.nz())
    throw Error(std::string(what) + ": the field is not shaped like the whole grid");
  std::size_t c = 0;
  for (int r = 0; r < d_.ranks(); ++r) {
    const Block& b = d_.block(r);
    for (int k = b.k0; k < b.k1; ++k)
      for (int j = b.j0; j < b.j1; ++j)
        for (int i = 0; i < d_.nx(); ++i) global(i, j, k) = all[c++];
  }
}

void DistributedGrid::gather(const Field& local, Field& global, int root) const {
  const std::vector<double> send = packed_block(local);
  std::vector<int> counts, displs;
  cell_counts(counts, displs);
  std::vector<double> all(rank_ == root ? static_cast<std::size_t>(d_.nx()) * line_position_.size() : 0);
  MPI_Gatherv(send.data(), static_cast<int>(send.size()), MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE,
              root, comm_);
  if (rank_ == root) unpack_whole(all, global, "gather");
}

void DistributedGrid::allgather(const Field& local, Field& global) const {
  const std::vector<double> send = packed_block(local);
  std::vector<int> counts, displs;
  cell_counts(counts, displs);
  std::vector<double> all(static_cast<std::size_t>(d_.nx()) * line_position_.size());
  MPI_Allgatherv(send.data(), static_cast<int>(send.size()), MPI_DOUBLE, all.data(), counts.data(), displs.data(),
                 MPI_DOUBLE, comm_);
  unpack_whole(all, global, "allgather");
}

void DistributedGrid::own_part(const Field& global, Field& local) const {
  if (global.nx() != d_.nx() || global.ny() != d_.ny() || global.nz() != d_.nz())
    throw Error("own_part: the field is not shaped like the whole grid");
  const Block& b = block();
  for (int k = 0; k < b.nz(); ++k)
    for (int j = 0; j < b.ny(); ++j)
      for (int i = 0; i < d_.nx(); ++i) local(i, j, k) = global(i, b.j0 + j, b.k0 + k);
}

void DistributedGrid::scatter(const Field& global, Field& local, int root) const {
  std::vector<double> all;
  if (rank_ == root) {
    if (global.nx() != d_.nx() || global.ny() != d_.ny() || global.nz() != d_.nz())
      throw Error("scatter: the root's field is not shaped like the whole grid");
    all.reserve(static_cast<std::size_t>(d_.nx()) * line_position_.size());
    for (int r = 0; r < d_.ranks(); ++r) {
      const Block& b = d_.block(r);
      for (int k = b.k0; k < b.k1; ++k)
        for (int j = b.j0; j < b.j1; ++j)
          for (int i = 0; i < d_.nx(); ++i) all.push_back(global(i, j, k));
    }
  }
  std::vector<int> counts(counts_), displs(displs_);
  for (std::size_t r = 0; r < counts.size(); ++r) counts[r] *= d_.nx(), displs[r] *= d_.nx();
  const Block& mine = block();
  std::vector<double> recv(static_cast<std::size_t>(d_.nx()) * static_cast<std::size_t>(mine.ny() * mine.nz()));
  MPI_Scatterv(all.data(), counts.data(), displs.data(), MPI_DOUBLE, recv.data(), static_cast<int>(recv.size()), MPI_DOUBLE,
               root, comm_);
  std::size_t c = 0;
  for (int k = 0; k < mine.nz(); ++k)
    for (int j = 0; j < mine.ny(); ++j)
      for (int i = 0; i < d_.nx(); ++i) local(i, j, k) = recv[c++];
}

}  // namespace finverse::cfd
