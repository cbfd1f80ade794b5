// One CMA-ES run (cmaes_run.hpp): pagmo::cmaes configured for the fit, driven by the shared loop.
#include "fit/cmaes_run.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "fit/errors.hpp"

namespace finverse::fit {

int default_cmaes_population(int parameter_count) {
  return std::max(5, 4 + static_cast<int>(std::floor(3 * std::log(std::max(1, parameter_count)))));
}

pagmo::cmaes make_cmaes(const CmaesOptions& options) {
  if (!(options.sigma0 > 0 && options.sigma0 <= 1))
    throw InvalidInput("cmaes: sigma0 must be in (0, 1], got " + std::to_string(options.sigma0));
  // ftol = xtol = 0: pagmo's own exits would return an unchanged population, silently; the
  // fit's stopping rule and generation cap decide instead. Learning rates automatic (-1).
  try {
    return pagmo::cmaes(1u, -1, -1, -1, -1, options.sigma0, 0.0, 0.0, /*memory=*/true,
                        /*force_bounds=*/true, options.seed);
  } catch (const std::invalid_argument& e) {
    throw InvalidInput(std::string("cmaes: bad settings: ") + e.what());
  }
}

RunResult run_cmaes(const ParameterSpace& space, const ResidualFunction& function,
                    const CmaesOptions& options, FinalPopulation* final_population) {
  if (options.population < 5)
    throw InvalidInput("cmaes: population must be >= 5, got " + std::to_string(options.population));
  PagmoStepper<pagmo::cmaes> stepper(make_cmaes(options));
  return run_evolution("cmaes", stepper, space, function, options, final_population);
}

}  // namespace finverse::fit
