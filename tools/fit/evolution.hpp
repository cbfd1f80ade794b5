// The generation loop shared by the GA and CMA-ES runs (DESIGN.md section 5.4): a seeded initial
// population evaluated in parallel, then one pagmo generation per step, with the history, the
// stopping rule (best objective changed by less than stop_tolerance over stop_window
// generations), progress and a checkpoint state after every generation.
//
// Parallel evaluation: pagmo's sga and cmaes create a whole generation before evaluating any of
// it (upstream src/algorithms/sga.cpp step 5, cmaes.cpp step 3). So each step first evolves
// copies of the algorithm and population against a problem that serves cached values and
// records the misses (answering a dummy), evaluates the recorded vectors in parallel into the
// cache, and then evolves the real algorithm and population, every request now a cache hit. The
// real evolve sees exactly the values serial evaluation would give.
#pragma once

#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <pagmo/population.hpp>
#include <pagmo/s11n.hpp>

#include "fit/fit_result.hpp"
#include "fit/parameter_space.hpp"
#include "fit/residual_function.hpp"

namespace finverse::fit {

struct EvolutionOptions {
  int population = 0;  // individuals; the GA needs an even number >= 2, CMA-ES >= 5
  int max_generations = 200;
  unsigned seed = 0;
  int threads = 2;
  double stop_tolerance = 0.01;  // relative change of the best objective ...
  int stop_window = 10;          // ... over this many generations; tolerance <= 0 disables it
  std::function<void(const GenerationRecord&)> progress;
  // Called after every generation with the run's full state; pass it back as `resume` to
  // continue as if never interrupted.
  std::function<void(const nlohmann::json& state)> checkpoint;
  const nlohmann::json* resume = nullptr;
};

// Scaled population at the end of a run, for tests and diagnostics.
struct FinalPopulation {
  std::vector<Eigen::VectorXd> x;
  std::vector<double> f;
};

// The algorithm-specific part: one generation of a pagmo algorithm, and its state.
class GenerationStepper {
 public:
  virtual ~GenerationStepper() = default;
  // Evolves a copy of the algorithm and of `population` one generation; the result is discarded.
  virtual void probe(const pagmo::population& population) const = 0;
  virtual pagmo::population step(pagmo::population population) = 0;
  virtual std::string save() const = 0;  // serialized algorithm state (random engine included)
  virtual void load(const std::string& state) = 0;
};

// A GenerationStepper for a pagmo algorithm class with evolve() and boost serialization (sga,
// cmaes), evolving one generation per step (the algorithm is built with gen = 1).
template <class Algorithm>
class PagmoStepper final : public GenerationStepper {
 public:
  explicit PagmoStepper(Algorithm algorithm) : algorithm_(std::move(algorithm)) {}
  void probe(const pagmo::population& population) const override {
    Algorithm copy = algorithm_;
    copy.evolve(population);
  }
  pagmo::population step(pagmo::population population) override {
    return algorithm_.evolve(std::move(population));
  }
  std::string save() const override {
    std::ostringstream out;
    {
      boost::archive::binary_oarchive archive(out);
      archive << algorithm_;
    }
    return out.str();
  }
  void load(const std::string& state) override {
    std::istringstream in(state);
    boost::archive::binary_iarchive archive(in);
    archive >> algorithm_;
  }
  const Algorithm& algorithm() const { return algorithm_; }

 private:
  Algorithm algorithm_;
};

// n points uniform in the scaled box from a 64-bit Mersenne twister seeded with `seed`
// (53-bit mantissa by hand, so the sample does not depend on the standard library).
std::vector<Eigen::VectorXd> sample_initial_population(const ParameterSpace& space, int count,
                                                       unsigned seed);

// Runs `stepper` until the stopping rule or the generation cap. `method` goes into the result.
RunResult run_evolution(const std::string& method, GenerationStepper& stepper,
                        const ParameterSpace& space, const ResidualFunction& function,
                        const EvolutionOptions& options, FinalPopulation* final_population = nullptr);

// Whether the history meets the stopping rule: best0 is the initial population's best.
bool stopping_rule_met(double best0, const std::vector<GenerationRecord>& history,
                       double tolerance, int window);

}  // namespace finverse::fit
