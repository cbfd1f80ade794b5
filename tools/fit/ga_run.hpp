// One run of the real-coded genetic algorithm of the fit (DESIGN.md section 5.4, the seed
// paper's procedure): pagmo::sga with tournament selection, SBX crossover, polynomial mutation
// and pure elitism (parents and offspring pooled, the best kept), one generation per step so
// that the run has a history, progress and a checkpoint per generation (evolution.hpp), and the
// offspring of a generation evaluated in parallel.
#pragma once

#include <pagmo/algorithms/sga.hpp>

#include "fit/evolution.hpp"

namespace finverse::fit {

struct GaOptions : EvolutionOptions {
  double crossover_probability = 0.9;
  double crossover_eta = 10;         // SBX distribution index, [1, 100]
  double mutation_probability = 0;   // per gene; 0 = 1 / parameter count
  double mutation_eta = 20;          // polynomial mutation distribution index, [1, 100]
  int tournament_size = 2;
};

// The pagmo algorithm a run uses (one generation per evolve call), for tests that compare
// against plain serial pagmo.
pagmo::sga make_sga(const GaOptions& options, int parameter_count);

// Throws InvalidInput for an odd or too small population (SBX pairs parents) or bad operator
// settings.
RunResult run_ga(const ParameterSpace& space, const ResidualFunction& function,
                 const GaOptions& options, FinalPopulation* final_population = nullptr);

}  // namespace finverse::fit
