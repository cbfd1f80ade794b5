// The multi-run inverse fit (DESIGN.md section 5.4, issue 31): several independent seeded runs of
// the GA and/or CMA-ES, a Levenberg-Marquardt polish from every run's champion, the overall best
// by least squares (by the distance objective without polish), and the uncertainty there. With
// a checkpoint path the state is saved after every generation and every finished run; `resume`
// continues from it to the result an uninterrupted fit gives. Same seed and options give a
// bitwise-identical FitResult for any thread count (wall times aside).
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "fit/fit_result.hpp"
#include "fit/levenberg_marquardt.hpp"
#include "fit/parameter_space.hpp"
#include "fit/residual_function.hpp"
#include "fit/uncertainty.hpp"

namespace finverse::fit {

struct FitOptions {
  int population = 0;        // GA; 0 = 8 per unknown (always even, as SBX needs)
  int cmaes_population = 0;  // CMA-ES lambda; 0 = 4 + floor(3 ln n) (default_cmaes_population)
  int max_generations = 200;
  int runs = 6;              // per method
  unsigned seed = 1;         // runs use seed, seed + 1, ... (the same seeds for each method)
  int threads = 2;
  double stop_tolerance = 0.01;
  int stop_window = 10;
  std::vector<std::string> methods{"ga"};  // "ga" and/or "cmaes", run in this order
  bool polish = true;
  LmOptions polish_options;  // its threads are replaced by `threads`
  UncertaintyOptions uncertainty;
  std::optional<std::filesystem::path> checkpoint;
  bool resume = false;  // continue from `checkpoint` when it exists (InvalidInput if it is another fit's)
  // After every generation: run index (0-based over all methods), method, the record, and an
  // estimate of the seconds left (generation caps assumed, so an upper bound).
  std::function<void(int run, const std::string& method, const GenerationRecord& record,
                     double eta_seconds)>
      progress;
};

// objective: "dynamic" | "quasi_static", carried into the result. explore (optional): a cheaper
// approximation of `function` (the same parameters and residuals) for the GA and CMA-ES to
// explore with; the polish, the champion's evaluation and the intervals always use `function`,
// so the answer is function's optimum (issue 45, goal 8: linearised increments explore, Newton's
// decide).
FitResult run_fit(const ParameterSpace& space, const ResidualFunction& function, const FitOptions& options,
                  const std::string& objective, const ResidualFunction* explore = nullptr);

}  // namespace finverse::fit
