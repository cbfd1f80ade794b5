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

// gather and allgather: every rank's interior packed line by line at its place in one gathered
// array (rank order; counts and offsets in doubles), which is then unpacked into the whole field.
// The array is scratch kept between calls (a whole-flow run gathers several fields per step, and
// a fresh array of that size costs its page faults every time), and this rank's part is packed
// into it in place, so a field is copied twice, once in and once out, a line at a time.
void DistributedGrid::pack_block(const Field& local, double* dst) const {
  const Block& mine = block();
  const int nx = d_.nx();
  for (int k = 0; k < mine.nz(); ++k)
    for (int j = 0; j < mine.ny(); ++j, dst += nx) std::copy_n(&local(0, j, k), nx, dst);
}

void DistributedGrid::cell_counts(std::vector<int>& counts, std::vector<int>& displs) const {
  counts = counts_, displs = displs_;
  for (std::size_t r = 0; r < counts.size(); ++r) counts[r] *= d_.nx(), displs[r] *= d_.nx();
}

void DistributedGrid::unpack_whole(const double* all, Field& global) const {
  const int nx = d_.nx();
  for (int r = 0; r < d_.ranks(); ++r) {
    const Block& b = d_.block(r);
    for (int k = b.k0; k < b.k1; ++k)
      for (int j = b.j0; j < b.j1; ++j, all += nx) std::copy_n(all, nx, &global(0, j, k));
  }
}

void DistributedGrid::check_whole(const Field& global, const char* what) const {
  if (global.nx() != d_.nx() || global.ny() != d_.ny() || global.nz() != d_.nz())
    throw Error(std::string(what) + ": the field is not shaped like the whole grid");
}

void DistributedGrid::gather(const Field& local, Field& global, int root) const {
  std::vector<int> counts, displs;
  cell_counts(counts, displs);
  std::vector<double>& all = cells_;
  all.resize(rank_ == root ? static_cast<std::size_t>(d_.nx()) * line_position_.size() : static_cast<std::size_t>(counts[rank_]));
  double* mine = all.data() + (rank_ == root ? displs[rank_] : 0);
  pack_block(local, mine);
  if (rank_ == root)
    MPI_Gatherv(MPI_IN_PLACE, 0, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE, root, comm_);
  else
    MPI_Gatherv(mine, counts[rank_], MPI_DOUBLE, nullptr, nullptr, nullptr, MPI_DOUBLE, root, comm_);
  if (rank_ != root) return;
  check_whole(global, "gather");  // after the collective, so that the other ranks are not left waiting in it
  unpack_whole(all.data(), global);
}

void DistributedGrid::allgather(const Field& local, Field& global) const {
  std::vector<int> counts, displs;
  cell_counts(counts, displs);
  std::vector<double>& all = cells_;
  all.resize(static_cast<std::size_t>(d_.nx()) * line_position_.size());
  pack_block(local, all.data() + displs[rank_]);
  MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE, comm_);
  check_whole(global, "allgather");
  unpack_whole(all.data(), global);
}

void DistributedGrid::own_part(const Field& global, Field& local) const {
  check_whole(global, "own_part");
  const Block& b = block();
  for (int k = 0; k < b.nz(); ++k)
    for (int j = 0; j < b.ny(); ++j) std::copy_n(&global(0, b.j0 + j, b.k0 + k), d_.nx(), &local(0, j, k));
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
