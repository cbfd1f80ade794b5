// fin-fit-bench: the inverse-fit benchmark (results/bench/fit.json, issue 31): GA, CMA-ES and
// GA + Levenberg-Marquardt polish to 1 % on the hybrid plate twin, evaluations per second of the
// dynamic and quasi-static objectives, and the parallel speed-up of a generation, all in one run
// (tools/fit/validation/fit_bench.hpp). A thin front end: the benchmark lives in the library so
// that tests can run it small. Exit 0 when every goal is met, 1 when one is missed, 2 on error.
//
//   fin-fit-bench --case data/cases/hybrid_plate_small_heave.json --out results/bench/fit.json --threads 2
//
// fin-fit-bench fin_rate: eq. (2) evaluations per second on a case's fin, the converged Newton
// increment against the linearised one (results/bench/fit_fin_rate.json, issue 45 goal 8;
// tools/fit/validation/fin_rate_bench.hpp):
//
//   fin-fit-bench --threads 2 fin_rate --mesh results/tiny/mesh.h5 --motion results/tiny/motion.h5
//       --loads results/tiny/loads.h5 --materials data/cases/trout_fin_materials.json
//       --out results/bench/fit_fin_rate.json
#include <CLI/CLI.hpp>
#include <chrono>
#include <string>

#include "core/cli.hpp"
#include "core/summary.hpp"
#include "fit/errors.hpp"
#include "fit/validation/fin_rate_bench.hpp"
#include "fit/validation/fit_bench.hpp"

int main(int argc, char** argv) {
  CLI::App app{"fin-fit-bench: inverse-fit optimisers, objective cost and parallel speed-up on the hybrid plate twin"};
  finverse::cli::Standard standard(app, "fin-fit-bench");
  finverse::fit::validation::FitBenchOptions o;
  std::string case_file, out = "results/bench/fit.json";
  app.add_option("--case", case_file,
                 "data/cases/hybrid_plate_small_heave.json (the fit validations' twin; required without fin_rate)");
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

  namespace v = finverse::fit::validation;
  v::FinRateOptions fr;
  fr.files.instant_count = 2;  // the default case's (config.schema.yaml fit.flags)
  std::string fr_loads, fr_out = "results/bench/fit_fin_rate.json", fr_base = "stress_free";
  auto* rate = app.add_subcommand("fin_rate", "eq. (2) evaluations per second on a case's fin: Newton vs linear");
  rate->add_option("--mesh", fr.files.mesh, "mesh.h5")->required();
  rate->add_option("--motion", fr.files.motion, "motion.h5 (the target)")->required();
  rate->add_option("--loads", fr_loads, "loads.h5")->required();
  rate->add_option("--materials", fr.files.materials, "materials JSON")->required();
  rate->add_option("--instant-count", fr.files.instant_count, "instants of eq. (2) (the default case's: 2)")
      ->capture_default_str();
  rate->add_option("--base", fr_base, "carried or stress_free (the pipeline's)")
      ->check(CLI::IsMember({"carried", "stress_free"}))
      ->capture_default_str();
  rate->add_option("--points", fr.points, "seeded points evaluated by each route")->capture_default_str();
  rate->add_option("--spread", fr.spread, "moduli within this factor of the materials file's")->capture_default_str();
  rate->add_option("--seed", fr.seed, "seed of the points")->capture_default_str();
  rate->add_option("--out", fr_out, "benchmark file")->capture_default_str();

  return finverse::cli::run(app, standard, argc, argv, [&]() -> int {
    const auto start = std::chrono::steady_clock::now();
    if (rate->parsed()) {
      fr.files.loads = fr_loads;
      fr.files.stress_free_base = fr_base == "stress_free";
      fr.threads = finverse::cli::threads_in_use();
      finverse::Summary s = v::run_fin_rate_bench(fr);
      s.set_timing(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), fr.threads);
      s.write(fr_out);
      return s.pass() ? 0 : 1;
    }
    if (case_file.empty()) throw finverse::fit::InvalidInput("--case: required (the hybrid plate case file)");
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
