// fin-fit-bench: the inverse-fit benchmark (results/bench/fit.json, issue 31): GA, CMA-ES and
// GA + Levenberg-Marquardt polish to 1 % on the hybrid plate twin, evaluations per second of the
// dynamic and quasi-static objectives, and the parallel speed-up of a generation, all in one run
// (tools/fit/validation/fit_bench.hpp). A thin front end: the benchmark lives in the library so
// that tests can run it small. Exit 0 when every goal is met, 1 when one is missed, 2 on error.
//
//   fin-fit-bench --case data/cases/hybrid_plate_small_heave.json --out results/bench/fit.json --threads 2
#include <CLI/CLI.hpp>
#include <chrono>
#include <string>

#include "core/cli.hpp"
#include "core/summary.hpp"
#include "fit/validation/fit_bench.hpp"

int main(int argc, char** argv) {
  CLI::App app{"fin-fit-bench: inverse-fit optimisers, objective cost and parallel speed-up on the hybrid plate twin"};
  finverse::cli::Standard standard(app, "fin-fit-bench");
  finverse::fit::validation::FitBenchOptions o;
  std::string case_file, out = "results/bench/fit.json";
  app.add_option("--case", case_file, "data/cases/hybrid_plate_small_heave.json (the fit validations' twin)")
      ->required();
  app.add_option("--out", out, "benchmark file")->capture_default_str();
  app.add_option("--objective", o.objective, "the arms' objective: dynamic (eq. 1) or quasi_static (eq. 2)")
      ->capture_default_str();
  app.add_option("--nx", o.nx, "plate cells along the chord")->capture_default_str();
  app.add_option("--nz", o.nz, "plate cells along the span")->capture_default_str();
  app.add_option("--periods", o.periods, "periods simulated from rest")->capture_default_str();
  app.add_option("--steps-per-period", o.steps_per_period, "eq. (1) time steps per period")->capture_default_str();
  app.add_option("--compared-frames", o.compared_frames, "eq. (1): frames compared over the last period")
      ->capture_default_str();
  app.add_option("--instants", o.instants, "eq. (2): mid-swing instants")->capture_default_str();
  app.add_option("--load-density", o.load_scale, "fluid density of the thin-airfoil loads (case: 1)")
      ->capture_default_str();
  app.add_option("--goal", o.goal, "relative error every parameter must reach")->capture_default_str();
  app.add_option("--seed", o.seed, "seed of every arm")->capture_default_str();
  app.add_option("--population", o.ga_population, "GA population (even)")->capture_default_str();
  app.add_option("--cmaes-population", o.cmaes_population, "CMA-ES lambda (0: 4 + 3 ln n)")->capture_default_str();
  app.add_option("--max-evaluations", o.max_evaluations, "per arm: stop (not reached) past this")
      ->capture_default_str();
  app.add_option("--max-arm-seconds", o.max_arm_seconds, "per arm: stop (not reached) past this wall time")
      ->capture_default_str();
  app.add_option("--polish-every", o.polish_every, "GA + polish: generations between polishes")->capture_default_str();
  app.add_option("--polish-evaluations", o.polish_max_evaluations, "evaluations per polish (0: 20 (n + 1))")
      ->capture_default_str();
  app.add_option("--rate-points", o.rate_points, "random points timed per objective")->capture_default_str();
  app.add_option("--rate-repeats", o.rate_repeats, "eq. (2) passes over the random points")->capture_default_str();
  app.add_option("--speedup-repeats", o.speedup_repeats, "timings per thread count (the fastest counts)")
      ->capture_default_str();
  app.add_option("--speedup-dynamic-population", o.speedup_dynamic_population,
                 "eq. (1) individuals timed on 1 and 2 threads, reported only (0: skip)")
      ->capture_default_str();
  app.add_option("--speedup-population", o.speedup_population, "individuals of the timed generation (0: --population)")
      ->capture_default_str();
  bool no_rate = false, no_speedup = false;
  app.add_option("--arms", o.arms, "optimiser arms to run, in order (none: --arms '')")
      ->delimiter(',')
      ->capture_default_str();
  app.add_flag("--no-rate", no_rate, "skip the evaluations-per-second part");
  app.add_flag("--no-speedup", no_speedup, "skip the speed-up part");

  return finverse::cli::run(app, standard, argc, argv, [&]() -> int {
    const auto start = std::chrono::steady_clock::now();
    o.case_file = case_file;
    o.threads = finverse::cli::threads_in_use();
    o.rate = !no_rate;
    o.speedup = !no_speedup;
    finverse::Summary s = finverse::fit::validation::run_fit_bench(o);
    s.set_timing(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), o.threads);
    s.write(out);
    return s.pass() ? 0 : 1;
  });
}
