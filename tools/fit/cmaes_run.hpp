// One run of CMA-ES (the fit's second arm, DESIGN.md section 5.4): pagmo::cmaes with memory, so
// that one generation per evolve call continues the same adaptation, and with the box enforced
// (the FEM must never see parameters outside the bounds). pagmo's cmaes samples the whole
// generation before evaluating it (upstream src/algorithms/cmaes.cpp, steps 1 and 3), so its
// generations are evaluated in parallel like the GA's (evolution.hpp). CMA-ES keeps no elite:
// the run's best is the best ever evaluated.
#pragma once

#include <pagmo/algorithms/cmaes.hpp>

#include "fit/evolution.hpp"

namespace finverse::fit {

struct CmaesOptions : EvolutionOptions {
  double sigma0 = 0.3;  // initial step, as a fraction of each scaled bound's width
};

// Default population (lambda) for n unknowns: 4 + floor(3 ln n) (Hansen), at least 5 (pagmo).
int default_cmaes_population(int parameter_count);

pagmo::cmaes make_cmaes(const CmaesOptions& options);

// Throws InvalidInput for a population below 5 or a sigma0 outside (0, 1].
RunResult run_cmaes(const ParameterSpace& space, const ResidualFunction& function,
                    const CmaesOptions& options, FinalPopulation* final_population = nullptr);

}  // namespace finverse::fit
