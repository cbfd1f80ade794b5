// The multi-run fit (fit_driver.hpp).
#include "fit/fit_driver.hpp"

#include <chrono>
#include <cmath>
#include <limits>

#include "fit/checkpoint.hpp"
#include "fit/cmaes_run.hpp"
#include "fit/errors.hpp"
#include "fit/ga_run.hpp"
#include "fit/population_evaluation.hpp"
#include "fit/rank_pool.hpp"

namespace finverse::fit {

namespace {

constexpr const char* checkpoint_format = "finverse/fit-checkpoint";
constexpr int checkpoint_version = 2;  // 2: the uncertainty's misfit correlation

// Everything the result depends on; a checkpoint is only resumed for the same fingerprint.
// Threads are left out on purpose: the result does not depend on them.
nlohmann::json fingerprint(const ParameterSpace& space, const ResidualFunction& function,
                           const FitOptions& o, const std::string& objective, int ga_population,
                           int cmaes_population) {
  nlohmann::json parameters = nlohmann::json::array();
  for (const Parameter& p : space.parameters())
    parameters.push_back({{"name", p.name},
                          {"lower", pack_doubles(&p.lower, 1)},
                          {"upper", pack_doubles(&p.upper, 1)},
                          {"scale", to_string(p.scale)}});
  const LmOptions& lm = o.polish_options;
  return {{"objective", objective},
          {"parameters", parameters},
          {"residual_count", function.residual_count()},
          {"population", ga_population},
          {"cmaes_population", cmaes_population},
          {"max_generations", o.max_generations},
          {"runs", o.runs},
          {"seed", o.seed},
          {"stop_tolerance", pack_doubles(&o.stop_tolerance, 1)},
          {"stop_window", o.stop_window},
          {"methods", o.methods},
          {"polish", o.polish},
          {"lm", {lm.max_evaluations, pack_doubles(&lm.reduction_tolerance, 1),
                  pack_doubles(&lm.step_tolerance, 1), pack_doubles(&lm.fd_step, 1), lm.central,
                  pack_doubles(&lm.initial_damping, 1)}}};
}

struct CompletedRun {
  RunResult run;
  std::optional<Uncertainty> uncertainty;  // at the polished point
};

// The finished runs and the interrupted one's state from a checkpoint of the same fit, if any.
void resume_from(const std::filesystem::path& checkpoint, const nlohmann::json& print,
                 std::vector<CompletedRun>& completed, std::optional<nlohmann::json>& current) {
  std::optional<nlohmann::json> saved = read_checkpoint(checkpoint);
  if (!saved) return;
  const std::string where = checkpoint.string();
  if (!saved->is_object() || saved->value("format", "") != checkpoint_format ||
      saved->value("version", 0) != checkpoint_version)
    throw InvalidInput(where + ": not a finverse fit checkpoint (version " + std::to_string(checkpoint_version) + ")");
  if (saved->at("fingerprint") != print)
    throw InvalidInput(where +
                       ": checkpoint of a different fit (parameters, objective or "
                       "options differ); delete it or do not resume");
  for (const nlohmann::json& c : saved->at("runs")) {
    CompletedRun done{run_result_from_json(c.at("run")), std::nullopt};
    if (!c.at("uncertainty").is_null()) done.uncertainty = uncertainty_from_json(c.at("uncertainty"));
    completed.push_back(std::move(done));
  }
  if (!saved->at("current").is_null()) current = saved->at("current");
}

}  // namespace

FitResult run_fit(const ParameterSpace& space, const ResidualFunction& function, const FitOptions& options,
                  const std::string& objective, const ResidualFunction* explore) {
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  const int n = space.size();
  const std::optional<ResidualLayout> layout = function.residual_layout();  // for the intervals
  if (function.parameter_count() != n)
    throw InvalidInput("fit: the residual function takes " + std::to_string(function.parameter_count()) +
                       " parameters, the parameter space has " + std::to_string(n));
  if (options.runs < 1) throw InvalidInput("fit: runs must be >= 1");
  if (options.threads < 1) throw InvalidInput("fit: threads must be >= 1");
  if (options.methods.empty()) throw InvalidInput("fit: no optimiser method given (ga, cmaes)");
  for (const std::string& m : options.methods)
    if (m != "ga" && m != "cmaes")
      throw InvalidInput("fit: unknown method '" + m + "' (expected ga or cmaes)");
  const int ga_population = options.population > 0 ? options.population : 8 * n;
  const int cmaes_population =
      options.cmaes_population > 0 ? options.cmaes_population : default_cmaes_population(n);
  LmOptions lm_options = options.polish_options;
  lm_options.threads = options.threads;
  lm_options.moved = [&](const Eigen::VectorXd& z) { expect_near_everywhere(function, space.to_physical(z)); };

  if (explore && (explore->parameter_count() != n || explore->residual_count() != function.residual_count()))
    throw InvalidInput("fit: the exploring residual function differs from the fit's in its parameters or residuals");
  nlohmann::json print = fingerprint(space, function, options, objective, ga_population, cmaes_population);
  print["explore"] = explore != nullptr;
  const ResidualFunction& search = explore ? *explore : function;  // the GA's and CMA-ES's
  std::vector<CompletedRun> completed;
  std::optional<nlohmann::json> current;  // {"index", "state"} of an interrupted run
  if (options.checkpoint && options.resume) resume_from(*options.checkpoint, print, completed, current);

  auto save = [&](const nlohmann::json* state, int index) {
    if (!options.checkpoint) return;
    nlohmann::json runs = nlohmann::json::array();
    for (const CompletedRun& c : completed)
      runs.push_back({{"run", run_result_to_json(c.run)},
                      {"uncertainty", c.uncertainty ? uncertainty_to_json(*c.uncertainty) : nlohmann::json()}});
    nlohmann::json file = {{"format", checkpoint_format},
                           {"version", checkpoint_version},
                           {"fingerprint", print},
                           {"runs", std::move(runs)},
                           {"current", state ? nlohmann::json{{"index", index}, {"state", *state}}
                                             : nlohmann::json()}};
    write_checkpoint(*options.checkpoint, file);
  };

  const int total_runs = static_cast<int>(options.methods.size()) * options.runs;
  for (int index = static_cast<int>(completed.size()); index < total_runs; ++index) {
    const std::string& method = options.methods[index / options.runs];
    const unsigned seed = options.seed + static_cast<unsigned>(index % options.runs);

    EvolutionOptions e;
    e.population = method == "ga" ? ga_population : cmaes_population;
    e.max_generations = options.max_generations;
    e.seed = seed;
    e.threads = options.threads;
    e.stop_tolerance = options.stop_tolerance;
    e.stop_window = options.stop_window;
    nlohmann::json resume_state;
    if (current && current->at("index").get<int>() == index) {
      resume_state = current->at("state");
      e.resume = &resume_state;
    }
    if (options.checkpoint) e.checkpoint = [&](const nlohmann::json& state) { save(&state, index); };
    if (options.progress) {
      e.progress = [&](const GenerationRecord& record) {
        // Seconds per generation of this run, and of a whole run from those already finished.
        const double per_generation = record.wall_seconds / record.generation;
        double per_run = per_generation * options.max_generations;
        if (!completed.empty()) {
          per_run = 0;
          for (const CompletedRun& c : completed) per_run += c.run.wall_seconds + c.run.polish_wall_seconds;
          per_run /= static_cast<double>(completed.size());
        }
        const double eta = per_generation * (options.max_generations - record.generation) +
                           per_run * (total_runs - index - 1);
        options.progress(index, method, record, eta);
      };
    }

    CompletedRun done;
    if (method == "ga") {
      GaOptions g;
      static_cast<EvolutionOptions&>(g) = e;
      done.run = run_ga(space, search, g);
    } else {
      CmaesOptions c;
      static_cast<EvolutionOptions&>(c) = e;
      done.run = run_cmaes(space, search, c);
    }
    if (options.polish) {
      expect_near_everywhere(function, done.run.best_x);
      const LmResult lm = levenberg_marquardt(space, function, space.to_scaled(done.run.best_x), lm_options);
      done.run.polished_x = space.to_physical(lm.z);
      done.run.polished_objective = lm.objective;
      done.run.polished_sum_of_squares = lm.sum_of_squares;
      done.run.polish_evaluations = lm.evaluations;
      done.run.polish_wall_seconds = lm.wall_seconds;
      if (lm.jacobian.size() > 0)
        done.uncertainty = compute_uncertainty(space, lm.z, lm.residuals, lm.jacobian, options.uncertainty,
                                               layout ? &*layout : nullptr);
    }
    completed.push_back(std::move(done));
    current.reset();
    save(nullptr, index);
  }

  FitResult result;
  result.space = space;
  result.objective = objective;
  result.threads = options.threads;
  for (const CompletedRun& c : completed) {
    result.runs.push_back(c.run);
    result.evaluations += c.run.evaluations + c.run.polish_evaluations;
  }
  // The overall best: least squares after the polish (what the uncertainty describes), the
  // distance objective without it. Ties go to the earlier run.
  for (int i = 0; i < static_cast<int>(completed.size()); ++i) {
    const RunResult& r = completed[i].run;
    const double key = options.polish ? r.polished_sum_of_squares : r.best_objective;
    if (result.best_run < 0 ||
        key < (options.polish ? completed[result.best_run].run.polished_sum_of_squares
                              : completed[result.best_run].run.best_objective))
      result.best_run = i;
  }
  const CompletedRun& best = completed[result.best_run];
  if (options.polish && best.uncertainty) {
    result.best_x = best.run.polished_x;
    result.best_objective = best.run.polished_objective;
    result.best_sum_of_squares = best.run.polished_sum_of_squares;
    result.uncertainty = *best.uncertainty;
  } else {
    // No polish (or it failed at its start): r and the Jacobian at the champion. Always done at
    // the end, so a resumed fit counts the same evaluations.
    result.best_x = best.run.best_x;
    const Eigen::VectorXd z = space.to_scaled(result.best_x);
    const BatchEvaluation b = evaluate_batch(space, function, {z}, 1, true);
    result.evaluations += 1;
    result.best_objective = b.objective[0];
    if (b.failures == 0) {
      result.best_sum_of_squares = b.residuals[0].squaredNorm();
      const Eigen::MatrixXd jac = finite_difference_jacobian(space, function, z, b.residuals[0], lm_options.fd_step,
                                                             lm_options.central, options.threads, &result.evaluations);
      result.uncertainty =
          compute_uncertainty(space, z, b.residuals[0], jac, options.uncertainty, layout ? &*layout : nullptr);
    } else {
      result.best_sum_of_squares = std::numeric_limits<double>::infinity();
    }
  }
  result.wall_seconds = elapsed();
  return result;
}

}  // namespace finverse::fit
