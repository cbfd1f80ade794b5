// The fit's evaluations across MPI ranks (issue 48, deliverable 3). Every rank reads the same
// inputs and builds the same residual functions; rank 0 runs the optimisers, and each batch of
// evaluate_batch (a generation, the polish's Jacobian columns) is broadcast, rank r evaluating the
// vectors i with i mod size = r, results back by index. An evaluation is a pure function of its
// vector and of the state every rank shares (expect_near is broadcast too), so materials.h5 is the
// threaded run's byte for byte. pagmo2 has no MPI island, hence the distribution around our own
// batch evaluation. MPI is initialised only when a launcher's environment says so.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "fit/population_evaluation.hpp"
#include "fit/residual_function.hpp"

namespace finverse::fit {

// Whether this process was started by an MPI launcher with more than one rank in its job.
bool launched_by_mpi();

class RankPool {
 public:
  // Initialises MPI when launched_by_mpi() (MPI_THREAD_FUNNELED: only the main thread talks).
  // Throws fit::InvalidInput when launched by MPI and built without it.
  RankPool();
  // Rank 0 releases the serving ranks if it has not yet; then MPI is finalised.
  ~RankPool();
  RankPool(const RankPool&) = delete;
  RankPool& operator=(const RankPool&) = delete;

  // The pool of this process (nullptr: none, a plain threaded run).
  static RankPool* current();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool serving() const { return rank_ > 0; }

  // The functions the ranks evaluate, in the same order on every rank (nullptr entries allowed).
  // Every rank calls it once its inputs are read; the serving ranks then serve().
  void set_functions(std::vector<const ResidualFunction*> functions);
  std::optional<int> id_of(const ResidualFunction& function) const;

  // Rank 0: the batch over every rank (population_evaluation.hpp's contract).
  BatchEvaluation evaluate(int function, const ParameterSpace& space, const std::vector<Eigen::VectorXd>& scaled,
                           int threads, bool keep_residuals);
  // Rank 0: function.expect_near(physical) here and on every serving rank.
  void expect_near(int function, const Eigen::VectorXd& physical);
  // A serving rank: evaluates what rank 0 sends until it is released; a failure here aborts the
  // job (rank 0 would wait for ever). `space` is the fit's; the threads are rank 0's.
  void serve(const ParameterSpace& space);
  // Rank 0: releases the serving ranks (once; also done by the destructor).
  void release();

 private:
  int rank_ = 0, size_ = 1;
  bool released_ = true;  // until set_functions: the serving ranks are not serving yet
  std::vector<const ResidualFunction*> functions_;
  std::vector<long> counts_;  // rank 0: vectors each rank evaluated in distributed batches

  void serve_until_released(const ParameterSpace& space);
};

// function.expect_near(physical) on every rank of the current pool, or here alone without one.
void expect_near_everywhere(const ResidualFunction& function, const Eigen::VectorXd& physical);

}  // namespace finverse::fit
