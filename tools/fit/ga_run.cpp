// One GA run (ga_run.hpp): pagmo::sga configured for the fit, driven by the shared loop.
#include "fit/ga_run.hpp"

#include <stdexcept>

#include "fit/errors.hpp"

namespace finverse::fit {

pagmo::sga make_sga(const GaOptions& options, int parameter_count) {
  const double m = options.mutation_probability > 0 ? options.mutation_probability
                                                    : 1.0 / std::max(1, parameter_count);
  if (options.tournament_size < 1)
    throw InvalidInput("ga: tournament_size must be >= 1, got " + std::to_string(options.tournament_size));
  try {
    return pagmo::sga(1u, options.crossover_probability, options.crossover_eta, m, options.mutation_eta,
                      static_cast<unsigned>(options.tournament_size), "sbx", "polynomial", "tournament",
                      options.seed);
  } catch (const std::invalid_argument& e) {
    throw InvalidInput(std::string("ga: bad operator settings: ") + e.what());
  }
}

RunResult run_ga(const ParameterSpace& space, const ResidualFunction& function,
                 const GaOptions& options, FinalPopulation* final_population) {
  if (options.population < 2 || options.population % 2 != 0)
    throw InvalidInput("ga: population must be even and >= 2 (SBX crossover pairs parents), got " +
                       std::to_string(options.population));
  if (options.tournament_size > options.population)
    throw InvalidInput("ga: tournament_size exceeds the population");
  PagmoStepper<pagmo::sga> stepper(make_sga(options, space.size()));
  return run_evolution("ga", stepper, space, function, options, final_population);
}

}  // namespace finverse::fit
