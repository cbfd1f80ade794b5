// The distance objective J of a residual vector (residual_function.hpp): the weighted mean
// point-to-point distance, the quantity the GA and CMA-ES minimise.
#include "fit/residual_function.hpp"

#include <string>

#include "fit/errors.hpp"

namespace finverse::fit {

double mean_distance(const Eigen::VectorXd& r, const Eigen::VectorXd& sqrt_weights) {
  const Eigen::Index samples = sqrt_weights.size();
  if (r.size() != 3 * samples)
    throw InvalidInput("residual vector has " + std::to_string(r.size()) +
                       " entries, expected 3 x " + std::to_string(samples) + " node-samples");
  const double total_weight = sqrt_weights.squaredNorm();
  if (!(total_weight > 0)) throw InvalidInput("node weights sum to zero");
  // r_k already carries sqrt(w_k): sqrt(w_k) |r_k| = w_k |dx_k|.
  double sum = 0;
  for (Eigen::Index k = 0; k < samples; ++k) sum += sqrt_weights(k) * r.segment<3>(3 * k).norm();
  return sum / total_weight;
}

}  // namespace finverse::fit
