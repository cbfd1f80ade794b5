// fin-fit: the inverse fit of the fin's material parameters (DESIGN.md 5.4, issue 31). Exit 0 on
// success, 1 when a validation metric misses, 2 on bad input (one line; no materials.h5 written).
//   fin-fit run --mesh mesh.h5 --motion motion.h5 --loads loads.h5 --materials materials.json
//       --out materials.h5 [--summary fit_summary.json] [--parameters spec.json]
//       [--objective quasi_static|dynamic] [--instant-count 4] [--runs 6] [--methods ga,cmaes]
//   fin-fit evaluate (the run's problem flags) [--at E_membrane=2e6,nu=0.4]   misfit, no fit
//   fin-fit uniform_plate                                            sec. 3.3 twin, eq. (1)
//   fin-fit hybrid_plate --case data/cases/hybrid_plate_small_heave.json   eq. (1), eq. (2)
//   fin-fit noise | identifiability --case ...                       noise; no loads
//   fin-fit grade_twin_noise --materials-h5 s0.h5 s1.h5 ... --truth trout_fin_materials.json
//   fin-fit flap --reference data/reference/hessenthaler2017.json    flap modulus (issue 34)
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "core/cli.hpp"
#include "core/summary.hpp"
#include "fit/io/file_fit.hpp"
#include "fit/validation/fin_twin_grade.hpp"
#include "fit/validation/fin_twin_noise_grade.hpp"
#include "fit/validation/hessenthaler_flap_fit.hpp"
#include "fit/validation/hybrid_plate_fit.hpp"
#include "fit/validation/uniform_plate_fit.hpp"
#include "fit_file_commands.hpp"

namespace {

using finverse::apps::kOwnData;
using finverse::apps::ProblemFlags;
using finverse::apps::RunFlags;

// Writes <out-dir>/<case>/summary.json and prints the metrics; exit 0 when every graded metric
// passes, 1 otherwise.
int finish(finverse::Summary summary, const std::string& name, const std::filesystem::path& out_dir, double wall) {
  summary.set_timing(wall, finverse::cli::threads_in_use());
  const auto path = out_dir / name / "summary.json";
  std::filesystem::create_directories(path.parent_path());
  summary.write(path);
  for (const auto& m : summary.metrics()) {
    if (m.kind == "info") continue;
    std::cerr << "  " << m.name << " = " << m.value;
    if (m.reference) std::cerr << " (reference " << *m.reference << ", error " << m.error() << ")";
    if (auto p = m.pass()) std::cerr << (*p ? "  pass" : "  FAIL");
    std::cerr << "\n";
  }
  std::cerr << "fin-fit " << name << ": " << (summary.pass() ? "pass" : "FAIL") << ", " << wall << " s, wrote "
            << path.string() << "\n";
  return summary.pass() ? 0 : 1;
}

// The hybrid plate validation cases' flags (hybrid_plate, noise, identifiability).
void add_hybrid_plate_options(CLI::App* c, finverse::fit::validation::HybridPlateFitOptions& hp, std::string& case_file,
                              std::string& out_dir) {
  c->add_option("--case", case_file, "hybrid plate case, e.g. data/cases/hybrid_plate_small_heave.json")->required();
  c->add_option("--out-dir", out_dir, "directory that receives <case>/summary.json")->capture_default_str();
  c->add_option("--nx", hp.nx, "plate cells along the chord")->capture_default_str();
  c->add_option("--nz", hp.nz, "plate cells along the span")->capture_default_str();
  c->add_option("--periods", hp.periods, "periods simulated from rest")->capture_default_str();
  c->add_option("--steps-per-period", hp.steps_per_period, "time steps per period")->capture_default_str();
  c->add_option("--compared-frames", hp.compared_frames, "eq. (1): frames compared over the last period")
      ->capture_default_str();
  c->add_option("--instants", hp.instants, "eq. (2): mid-swing instants")->capture_default_str();
  c->add_option("--load-density", hp.load_scale, "fluid density of the thin-airfoil loads (case: 1)")
      ->capture_default_str();
  c->add_option("--runs", hp.fit.runs, "independent GA runs")->capture_default_str();
  c->add_option("--population", hp.fit.population, "GA population")->capture_default_str();
  c->add_option("--generations", hp.fit.max_generations, "generation cap")->capture_default_str();
  c->add_option("--seed", hp.fit.seed, "seed of the first run")->capture_default_str();
  c->add_option("--polish-evaluations", hp.fit.polish_options.max_evaluations,
                "evaluation cap of each Levenberg-Marquardt polish (0: 6 (n + 1))")
      ->capture_default_str();
  c->add_option("--noise-seeds", hp.noise_seeds, "noise: seeds")->capture_default_str();
  c->add_option("--materials-out", hp.materials_out, "hybrid_plate: also write the eq. (2) fit as materials.h5");
  c->add_option("--noise-objective", hp.noise_objective, "noise: dynamic or quasi_static")->capture_default_str();
}

// The fin twin's grading subcommands: one fit against the true materials, or a fit per noise seed.
struct GradeFlags {
  std::string graded, truth, twin_name = "fit_trout_twin";
  std::vector<std::string> noisy_fits;
  std::string noise_name = "fit_trout_noise";
};

std::pair<CLI::App*, CLI::App*> add_grade_commands(CLI::App& app, GradeFlags& g, std::string& out_dir) {
  auto* gc = app.add_subcommand("grade_twin", "fin twin: a fin-fit run's materials.h5 against the true materials");
  gc->add_option("--materials-h5", g.graded, "materials.h5 of fin-fit run on the twin's target")->required();
  gc->add_option("--name", g.twin_name, "case name (<out-dir>/<name>/summary.json)")->capture_default_str();
  auto* nc = app.add_subcommand("grade_twin_noise", "fin twin through tracking noise: fits of several seeds graded");
  nc->add_option("--materials-h5", g.noisy_fits, "materials.h5 of fin-fit run --target-noise, one per seed")
      ->required();
  nc->add_option("--name", g.noise_name, "case name (<out-dir>/<name>/summary.json)")->capture_default_str();
  for (auto* c : {gc, nc}) {
    c->add_option("--truth", g.truth, "materials JSON the target was computed with")->required();
    c->add_option("--out-dir", out_dir, "directory that receives <case>/summary.json")->capture_default_str();
  }
  return {gc, nc};
}

int run_grade(const GradeFlags& g, const CLI::App* which, const std::string& out_dir) {
  namespace v = finverse::fit::validation;
  using finverse::stage::Materials;
  const auto truth = finverse::fem::io::read_material_spec(g.truth);
  if (which->get_name() == "grade_twin") {
    auto summary = v::grade_fin_twin(finverse::stage::read<Materials>(g.graded), truth, g.twin_name);
    summary.parameters()["materials_h5"] = g.graded;
    summary.parameters()["truth"] = g.truth;
    return finish(std::move(summary), g.twin_name, out_dir, 0.0);
  }
  std::vector<Materials> fits;
  for (const auto& f : g.noisy_fits) fits.push_back(finverse::stage::read<Materials>(f));
  auto summary = v::grade_fin_twin_noise(fits, g.noisy_fits, truth, g.noise_name);
  summary.parameters()["materials_h5"] = g.noisy_fits;
  summary.parameters()["truth"] = g.truth;
  return finish(std::move(summary), g.noise_name, out_dir, 0.0);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fin-fit: Young's moduli of the fin's rays and membrane from its motion and loads"};
  finverse::cli::Standard standard(app, "fin-fit");
  standard.mpi = true;  // fin-fit run's evaluations across ranks (tools/fit/rank_pool.hpp)
  app.require_subcommand(1);

  ProblemFlags flags;
  RunFlags run;
  finverse::apps::add_run_command(app, flags, run);

  // The misfit at given values, without a fit.
  std::vector<std::string> at_values;
  auto* ev = app.add_subcommand("evaluate", "the objective at given parameter values, in total and per instant");
  finverse::apps::add_problem_options(ev, flags);
  ev->footer(kOwnData);
  ev->add_option("--at", at_values,
                 "NAME=VALUE (SI), e.g. --at E_membrane=2e6 --at nu=0.4; the materials file's "
                 "values for the others")
      ->delimiter(',');

  // Validation cases: the hybrid plate twin and its variants.
  finverse::fit::validation::HybridPlateFitOptions hp;
  std::string out_dir = "results/validation";
  std::string case_file;
  hp.fit.runs = 3;
  hp.fit.population = 40;
  hp.fit.max_generations = 60;
  std::vector<CLI::App*> cases;
  for (const auto& [name, what] : std::vector<std::pair<std::string, std::string>>{
           {"hybrid_plate", "hybrid plate twin: eq. (1) and eq. (2) fits, errors and speed ratio"},
           {"noise", "hybrid plate twin with noisy target: errors and 95% interval coverage"},
           {"identifiability", "hybrid plate, eq. (2) without loads: the modulus scale must be flagged"}}) {
    auto* c = app.add_subcommand(name, what);
    add_hybrid_plate_options(c, hp, case_file, out_dir);
    cases.push_back(c);
  }

  finverse::fit::validation::UniformPlateFitOptions up;
  up.fit.runs = 1;
  up.fit.population = 16;
  up.fit.max_generations = 15;
  auto* uc = app.add_subcommand("uniform_plate", "sec. 3.3 flexible pitching plate twin: E and nu by eq. (1)");
  uc->add_option("--out-dir", out_dir, "directory that receives <case>/summary.json")->capture_default_str();
  uc->add_option("--nx", up.nx, "plate cells along the chord")->capture_default_str();
  uc->add_option("--nz", up.nz, "plate cells along the span")->capture_default_str();
  uc->add_option("--periods", up.periods, "periods simulated from rest")->capture_default_str();
  uc->add_option("--steps-per-period", up.steps_per_period, "time steps per period")->capture_default_str();
  uc->add_option("--runs", up.fit.runs, "independent GA runs")->capture_default_str();
  uc->add_option("--population", up.fit.population, "GA population")->capture_default_str();
  uc->add_option("--generations", up.fit.max_generations, "generation cap")->capture_default_str();
  uc->add_option("--seed", up.fit.seed, "seed of the first run")->capture_default_str();
  uc->add_option("--polish-evaluations", up.fit.polish_options.max_evaluations,
                 "evaluation cap of each Levenberg-Marquardt polish (0: 6 (n + 1))")
      ->capture_default_str();

  GradeFlags grade;
  auto [gc, nc] = add_grade_commands(app, grade, out_dir);

  // The Hessenthaler (2017) flap: E from its measured buoyancy-only deflection (issue 34).
  finverse::fit::validation::FlapFitOptions fl;
  std::string flap_model = "shell";
  auto* fc = app.add_subcommand("flap", "Hessenthaler 2017 silicone flap: E from the buoyancy-only tip deflection");
  fc->add_option("--reference", fl.reference, "hessenthaler2017.json")->required();
  fc->add_option("--name", fl.name, "case name (<out-dir>/<name>/summary.json)")->capture_default_str();
  fc->add_option("--out-dir", out_dir, "directory that receives <name>/summary.json")->capture_default_str();
  fc->add_option("--model", flap_model, "graded model: beam or shell (both are in the mesh study)")
      ->check(CLI::IsMember({"beam", "shell"}))
      ->capture_default_str();
  fc->add_flag("--coarse", fl.coarse, "CI variant: the two coarsest meshes of each model");
  fc->add_option("--load-steps", fl.load_steps, "initial Newton load steps")->capture_default_str();

  return finverse::cli::run(app, standard, argc, argv, [&]() -> int {
    if (finverse::cli::mpi_launch_size() > 1 && !app.got_subcommand("run"))
      throw finverse::Error(
          "started by an MPI launcher: only fin-fit run spreads its evaluations over ranks; run "
          "this subcommand without mpirun");
    if (*fc) {
      const auto start = std::chrono::steady_clock::now();
      fl.model = finverse::fem::validation::parse_flap_model(flap_model);
      auto summary = finverse::fit::validation::run_hessenthaler_flap_fit(fl);
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return finish(std::move(summary), fl.name, out_dir, wall);
    }
    if (*gc || *nc) return run_grade(grade, *gc ? gc : nc, out_dir);
    if (*uc) {
      const auto start = std::chrono::steady_clock::now();
      up.fit.threads = finverse::cli::threads_in_use();
      auto summary = finverse::fit::validation::run_uniform_plate_fit(up);
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return finish(std::move(summary), "fit_uniform_plate", out_dir, wall);
    }
    for (auto* c : cases) {
      if (!*c) continue;
      namespace v = finverse::fit::validation;
      const auto start = std::chrono::steady_clock::now();
      hp.case_file = case_file;
      hp.fit.threads = finverse::cli::threads_in_use();
      const std::string name = c->get_name();
      auto summary = name == "hybrid_plate" ? v::run_hybrid_plate_fit(hp)
                     : name == "noise"      ? v::run_hybrid_plate_noise(hp)
                                            : v::run_hybrid_plate_identifiability(hp);
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return finish(std::move(summary), "fit_" + name, out_dir, wall);
    }
    finverse::fit::io::FileFitOptions& o = flags.o;
    finverse::apps::apply_flags(flags, run);
    if (*ev) {
      namespace io = finverse::fit::io;
      std::fputs(io::format_misfit(io::evaluate_misfit(o, io::parse_parameter_values(at_values))).c_str(), stdout);
      return 0;
    }
    o.fit.threads = finverse::cli::threads_in_use();
    const auto result = finverse::fit::io::run_fit_from_files(o, finverse::cli::effective_config(app));
    if (finverse::cli::mpi_launch_rank() > 0) return 0;  // a serving rank: rank 0 writes and says
    std::cerr << "fin-fit run: objective " << result.best_objective << " m after " << result.evaluations
              << " evaluations, wrote " << run.out << "\n";
    return 0;
  });
}
