// RankShare (rank_share.hpp) over an MPI communicator: the chunks of a shared loop gathered by
// MPI_Allgatherv, a failure's message broadcast from the lowest failing rank. FlowRanks installs
// one over MPI_COMM_WORLD for a whole-flow run (rank_pressure_system.hpp).
#pragma once

#include <mpi.h>

#include "cfd/parallel/rank_share.hpp"

namespace finverse::cfd {

class MpiRankShare : public RankShare {
 public:
  explicit MpiRankShare(MPI_Comm comm);
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  void allgather(unsigned char* data, const std::vector<std::size_t>& bytes) const override;
  std::string first_failure(bool failed, const std::string& message) const override;
  double max(double value) const override;

 private:
  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
};

}  // namespace finverse::cfd
