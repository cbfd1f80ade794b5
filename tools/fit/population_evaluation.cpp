// Parallel evaluation of a batch of scaled vectors (population_evaluation.hpp).
#include "fit/population_evaluation.hpp"

#include <omp.h>

#include <cmath>
#include <exception>
#include <limits>

#include "fit/errors.hpp"
#include "fit/rank_pool.hpp"

namespace finverse::fit {

namespace {

struct One {
  double objective = std::numeric_limits<double>::infinity();
  Eigen::VectorXd residuals;
  bool failed = true;
};

One evaluate_one(const ParameterSpace& space, const ResidualFunction& function,
                 const Eigen::VectorXd& z, bool keep_residuals) {
  One out;
  try {
    Eigen::VectorXd r = function.residuals(space.to_physical(z));
    const double j = mean_distance(r, function.sqrt_weights());
    if (std::isfinite(j) && r.allFinite()) {
      out.objective = j;
      out.failed = false;
      if (keep_residuals) out.residuals = std::move(r);
    }
  } catch (const Error&) {
    throw;  // bad input: every vector would fail the same way, so report it, do not hide it
  } catch (const std::exception&) {
    // The model failed for this vector (not converged, singular): the worst objective.
  }
  return out;
}

}  // namespace

BatchEvaluation evaluate_batch(const ParameterSpace& space, const ResidualFunction& function,
                               const std::vector<Eigen::VectorXd>& scaled, int threads,
                               bool keep_residuals) {
  RankPool* pool = RankPool::current();
  if (pool && pool->size() > 1 && scaled.size() > 1)
    if (const auto id = pool->id_of(function)) return pool->evaluate(*id, space, scaled, threads, keep_residuals);
  return evaluate_batch_here(space, function, scaled, threads, keep_residuals);
}

BatchEvaluation evaluate_batch_here(const ParameterSpace& space, const ResidualFunction& function,
                                    const std::vector<Eigen::VectorXd>& scaled, int threads, bool keep_residuals) {
  const int n = static_cast<int>(scaled.size());
  std::vector<One> results(scaled.size());
  if (threads <= 1 || n <= 1) {
    for (int i = 0; i < n; ++i) results[i] = evaluate_one(space, function, scaled[i], keep_residuals);
  } else {
    // Exceptions must not leave an OpenMP region: the first one is kept and rethrown.
    std::exception_ptr error;
#pragma omp parallel num_threads(threads)
    {
      // nthreads-var of this worker's implicit task only: nested regions (the FEM's) get one
      // thread, the caller's setting is untouched after the region.
      omp_set_num_threads(1);
#pragma omp for schedule(dynamic, 1)
      for (int i = 0; i < n; ++i) {
        try {
          results[i] = evaluate_one(space, function, scaled[i], keep_residuals);
        } catch (...) {
#pragma omp critical(finverse_fit_batch_error)
          if (!error) error = std::current_exception();
        }
      }
    }
    if (error) std::rethrow_exception(error);
  }
  BatchEvaluation out;
  out.objective.resize(scaled.size());
  if (keep_residuals) out.residuals.resize(scaled.size());
  for (int i = 0; i < n; ++i) {
    out.objective[i] = results[i].objective;
    if (results[i].failed) ++out.failures;
    if (keep_residuals) out.residuals[i] = std::move(results[i].residuals);
  }
  return out;
}

}  // namespace finverse::fit
