// Tracking noise on a motion (see tracking_noise.hpp).
#include "fit/io/tracking_noise.hpp"

#include <cmath>
#include <numbers>
#include <random>

namespace finverse::fit::io {

double sigma_for_mean_error(double mean_error) { return mean_error / (2 * std::sqrt(2 / std::numbers::pi)); }

stage::Motion with_tracking_noise(stage::Motion motion, double sigma, std::uint64_t seed) {
  // One stream over the file's flat order, so the noise does not depend on the thread count.
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0, sigma);
  for (double& x : motion.points.data) x += n(rng);
  motion.velocity = {};
  return motion;
}

}  // namespace finverse::fit::io
