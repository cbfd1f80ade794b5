// RankShare over MPI; see mpi_rank_share.hpp.
#include "cfd/parallel/mpi_rank_share.hpp"

#include <climits>

namespace finverse::cfd {

MpiRankShare::MpiRankShare(MPI_Comm comm) : comm_(comm) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

void MpiRankShare::allgather(unsigned char* data, const std::vector<std::size_t>& bytes) const {
  if (static_cast<int>(bytes.size()) != size_) throw Error("MpiRankShare::allgather: expected one byte count per rank");
  std::vector<int> counts(bytes.size()), displs(bytes.size());
  std::size_t at = 0;
  for (std::size_t r = 0; r < bytes.size(); ++r) {
    if (bytes[r] > static_cast<std::size_t>(INT_MAX) || at > static_cast<std::size_t>(INT_MAX))
      throw Error("MpiRankShare::allgather: more than 2 GB in one shared loop");
    counts[r] = static_cast<int>(bytes[r]);
    displs[r] = static_cast<int>(at);
    at += bytes[r];
  }
  MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, data, counts.data(), displs.data(), MPI_BYTE, comm_);
}

double MpiRankShare::max(double value) const {
  double m = value;
  MPI_Allreduce(&value, &m, 1, MPI_DOUBLE, MPI_MAX, comm_);
  return m;
}

std::string MpiRankShare::first_failure(bool failed, const std::string& message) const {
  int mine = failed ? rank_ : size_, first = size_;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm_);
  if (first == size_) return {};
  int length = rank_ == first ? static_cast<int>(message.size()) : 0;
  MPI_Bcast(&length, 1, MPI_INT, first, comm_);
  std::string text(static_cast<std::size_t>(length), '\0');
  if (rank_ == first) text = message;
  MPI_Bcast(text.data(), length, MPI_CHAR, first, comm_);
  return text;
}

}  // namespace finverse::cfd
