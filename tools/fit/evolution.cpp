// The generation loop shared by the GA and CMA-ES runs (evolution.hpp).
#include "fit/evolution.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <random>

#include <pagmo/problem.hpp>

#include "fit/checkpoint.hpp"
#include "fit/errors.hpp"
#include "fit/fitness_cache.hpp"
#include "fit/population_evaluation.hpp"

namespace finverse::fit {

namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

// What the pagmo problem shares with the loop (pagmo copies the problem into every population,
// so the state lives behind a shared pointer).
struct ProblemState {
  const ParameterSpace* space = nullptr;
  const ResidualFunction* function = nullptr;
  FitnessCache* cache = nullptr;
  std::pair<pagmo::vector_double, pagmo::vector_double> bounds;
  bool recording = false;
  std::vector<Eigen::VectorXd> recorded;  // misses of the probe, in request order
  FitnessCache pending;                   // the same, for finding repeats within one probe
  long fallback_failures = 0;
};

// The pagmo user-defined problem: objective values from the cache. While recording (the probe),
// a miss is noted and answered with a dummy; otherwise a miss (never expected) is evaluated here.
struct CachedProblem {
  std::shared_ptr<ProblemState> state;

  pagmo::vector_double fitness(const pagmo::vector_double& x) const {
    ProblemState& s = *state;
    const Eigen::VectorXd z = Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size()));
    if (std::optional<double> f = s.cache->peek(z)) {
      if (s.recording) s.cache->count_hit();
      return {*f};
    }
    if (s.recording) {
      if (s.pending.peek(z)) {
        s.cache->count_hit();  // a repeat within this generation: evaluated once
      } else {
        s.pending.insert(z, 0.0);
        s.recorded.push_back(z);
        s.cache->count_miss();
      }
      return {0.0};
    }
    const BatchEvaluation b = evaluate_batch(*s.space, *s.function, {z}, 1);
    s.cache->count_miss();
    s.fallback_failures += b.failures;
    s.cache->insert(z, b.objective[0]);
    return {b.objective[0]};
  }
  std::pair<pagmo::vector_double, pagmo::vector_double> get_bounds() const { return state->bounds; }
  std::string get_name() const { return "finverse fit objective"; }
};

std::vector<double> flatten(const std::vector<pagmo::vector_double>& rows) {
  std::vector<double> out;
  for (const auto& r : rows) out.insert(out.end(), r.begin(), r.end());
  return out;
}

nlohmann::json bytes_of(const std::string& s) {
  return nlohmann::json::binary(std::vector<std::uint8_t>(s.begin(), s.end()));
}

std::string string_of(const nlohmann::json& j) {
  const auto& b = j.get_binary();
  return std::string(b.begin(), b.end());
}

}  // namespace

std::vector<Eigen::VectorXd> sample_initial_population(const ParameterSpace& space, int count,
                                                       unsigned seed) {
  std::mt19937_64 engine(seed);
  const Eigen::VectorXd lo = space.scaled_lower(), hi = space.scaled_upper();
  std::vector<Eigen::VectorXd> out(static_cast<std::size_t>(count), Eigen::VectorXd(space.size()));
  for (auto& z : out)
    for (int i = 0; i < space.size(); ++i) {
      const double u = static_cast<double>(engine() >> 11) * 0x1.0p-53;  // [0, 1)
      z(i) = lo(i) + u * (hi(i) - lo(i));
    }
  return out;
}

bool stopping_rule_met(double best0, const std::vector<GenerationRecord>& history, double tolerance,
                       int window) {
  if (!(tolerance > 0) || window < 1) return false;
  const int g = static_cast<int>(history.size());
  if (g < window) return false;
  const double then = g == window ? best0 : history[g - window - 1].best;
  const double now = history.back().best;
  if (!std::isfinite(then)) return false;
  // <= so that an objective that reached exactly zero counts as converged.
  return then - now <= tolerance * std::abs(then);
}

RunResult run_evolution(const std::string& method, GenerationStepper& stepper,
                        const ParameterSpace& space, const ResidualFunction& function,
                        const EvolutionOptions& options, FinalPopulation* final_population) {
  const int n = space.size();
  const int np = options.population;
  if (function.parameter_count() != n)
    throw InvalidInput(method + ": the residual function takes " +
                       std::to_string(function.parameter_count()) + " parameters, the space has " +
                       std::to_string(n));
  if (np < 2) throw InvalidInput(method + ": population must be at least 2, got " + std::to_string(np));
  if (options.max_generations < 0)
    throw InvalidInput(method + ": max_generations must be >= 0");
  if (options.threads < 1) throw InvalidInput(method + ": threads must be >= 1");

  const auto start = std::chrono::steady_clock::now();
  double elapsed_before = 0;  // wall time before a restart
  auto wall = [&] {
    return elapsed_before +
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };

  FitnessCache cache;
  auto state = std::make_shared<ProblemState>();
  state->space = &space;
  state->function = &function;
  state->cache = &cache;
  {
    const Eigen::VectorXd lo = space.scaled_lower(), hi = space.scaled_upper();
    state->bounds.first.assign(lo.data(), lo.data() + n);
    state->bounds.second.assign(hi.data(), hi.data() + n);
  }
  pagmo::population pop(pagmo::problem(CachedProblem{state}), 0u, options.seed);

  RunResult run;
  run.method = method;
  run.seed = options.seed;
  double best0 = infinity;
  Eigen::VectorXd best_z = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::quiet_NaN());
  double best_f = infinity;
  long failures = 0;
  auto consider = [&](const pagmo::vector_double& x, double f) {
    if (f < best_f) {
      best_f = f;
      best_z = Eigen::Map<const Eigen::VectorXd>(x.data(), n);
    }
  };

  if (options.resume) {
    const nlohmann::json& s = *options.resume;
    if (s.at("method") != method || s.at("seed").get<unsigned>() != options.seed ||
        s.at("population").get<int>() != np || s.at("dimension").get<int>() != n)
      throw InvalidInput("checkpoint: the saved " + s.at("method").get<std::string>() +
                         " run differs from the requested one (method, seed, population or "
                         "parameter count)");
    stepper.load(string_of(s.at("algorithm")));
    const std::vector<double> x = unpack_doubles(s.at("x")), f = unpack_doubles(s.at("f"));
    for (int i = 0; i < np; ++i)
      pop.push_back(pagmo::vector_double(x.begin() + i * n, x.begin() + (i + 1) * n), {f[i]});
    const std::vector<double> cx = unpack_doubles(s.at("cache_x")), cf = unpack_doubles(s.at("cache_f"));
    for (std::size_t i = 0; i < cf.size(); ++i)
      cache.insert(Eigen::Map<const Eigen::VectorXd>(cx.data() + i * n, n), cf[i]);
    cache.restore_counts(s.at("hits").get<long>(), s.at("misses").get<long>());
    const RunResult saved = run_result_from_json(s.at("run"));
    run.history = saved.history;
    failures = saved.failures;
    elapsed_before = saved.wall_seconds;
    best0 = unpack_doubles(s.at("best0")).at(0);
    best_f = saved.best_objective;
    best_z = unpack_vector(s.at("best_z"));
  } else {
    const std::vector<Eigen::VectorXd> xs = sample_initial_population(space, np, options.seed);
    const BatchEvaluation b = evaluate_batch(space, function, xs, options.threads);
    failures += b.failures;
    for (int i = 0; i < np; ++i) {
      cache.insert(xs[i], b.objective[i]);
      cache.count_miss();
      pop.push_back(pagmo::vector_double(xs[i].data(), xs[i].data() + n), {b.objective[i]});
      consider(pop.get_x()[i], b.objective[i]);
    }
    best0 = best_f;
  }

  auto snapshot = [&] {
    run.best_x = space.to_physical(best_z);
    run.best_objective = best_f;
    run.evaluations = cache.misses();
    run.cache_hits = cache.hits();
    run.failures = failures + state->fallback_failures;
    run.wall_seconds = wall();
  };

  while (static_cast<int>(run.history.size()) < options.max_generations &&
         !stopping_rule_met(best0, run.history, options.stop_tolerance, options.stop_window)) {
    // (a) which vectors does this generation need?
    state->recording = true;
    state->recorded.clear();
    state->pending.clear();
    stepper.probe(pop);
    state->recording = false;
    // (b) evaluate them in parallel; insertion in request order keeps the cache deterministic
    const BatchEvaluation b = evaluate_batch(space, function, state->recorded, options.threads);
    failures += b.failures;
    for (std::size_t i = 0; i < state->recorded.size(); ++i) cache.insert(state->recorded[i], b.objective[i]);
    // (c) the real generation: every request is now a hit
    pop = stepper.step(std::move(pop));

    double sum = 0;
    int finite = 0;
    for (std::size_t i = 0; i < pop.size(); ++i) {
      const double f = pop.get_f()[i][0];
      consider(pop.get_x()[i], f);
      if (std::isfinite(f)) {
        sum += f;
        ++finite;
      }
    }
    GenerationRecord record;
    record.generation = static_cast<int>(run.history.size()) + 1;
    record.best = best_f;
    record.mean = finite ? sum / finite : infinity;
    record.evaluations = cache.misses();
    record.wall_seconds = wall();
    record.best_x = space.to_physical(best_z);
    run.history.push_back(record);

    if (options.checkpoint) {
      snapshot();
      std::vector<double> cx, cf;
      for (const auto& [z, f] : cache.entries()) {
        cx.insert(cx.end(), z.data(), z.data() + n);
        cf.push_back(f);
      }
      const std::vector<double> px = flatten(pop.get_x()), pf = flatten(pop.get_f());
      nlohmann::json s = {{"method", method},
                          {"seed", options.seed},
                          {"population", np},
                          {"dimension", n},
                          {"algorithm", bytes_of(stepper.save())},
                          {"x", pack_doubles(px.data(), px.size())},
                          {"f", pack_doubles(pf.data(), pf.size())},
                          {"cache_x", pack_doubles(cx.data(), cx.size())},
                          {"cache_f", pack_doubles(cf.data(), cf.size())},
                          {"hits", cache.hits()},
                          {"misses", cache.misses()},
                          {"best0", pack_doubles(&best0, 1)},
                          {"best_z", pack_vector(best_z)},
                          {"run", run_result_to_json(run)}};
      options.checkpoint(s);
    }
    if (options.progress) options.progress(record);
  }

  snapshot();
  run.converged = stopping_rule_met(best0, run.history, options.stop_tolerance, options.stop_window);
  if (final_population) {
    final_population->x.clear();
    final_population->f.clear();
    for (std::size_t i = 0; i < pop.size(); ++i) {
      final_population->x.push_back(Eigen::Map<const Eigen::VectorXd>(pop.get_x()[i].data(), n));
      final_population->f.push_back(pop.get_f()[i][0]);
    }
  }
  return run;
}

}  // namespace finverse::fit
