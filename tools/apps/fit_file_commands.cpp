// fin-fit's stage-file subcommands (fit_file_commands.hpp).
#include "fit_file_commands.hpp"

namespace finverse::apps {

void add_problem_options(CLI::App* c, ProblemFlags& f) {
  c->add_option("--mesh", f.mesh, "mesh.h5 (finverse/mesh; a structural mesh needs no /ibm surface)")->required();
  c->add_option("--motion", f.motion,
                "motion.h5: the target positions per time or load level; its root nodes drive "
                "the model")
      ->required();
  c->add_option("--loads", f.loads,
                "loads.h5 of fin-cfd, or nodal_loads.h5 (a structural load case: times or load "
                "levels and nodal forces); eq. (2) needs loads for the modulus scale");
  c->add_option("--materials", f.materials, "materials JSON: densities and the values of parameters not fitted")
      ->required();
  c->add_option("--parameters", f.parameters,
                "parameter specification JSON (default: E_membrane, E_ray<id> for every ray, nu)");
  c->add_option("--objective", f.o.objective,
                "quasi_static (paper eq. 2), dynamic (eq. 1) or static (load levels measured at rest)")
      ->check(CLI::IsMember({"quasi_static", "dynamic", "static"}))
      ->capture_default_str();
  c->add_option("--instants", f.o.instants, "quasi_static: instants t_j [s] (default: --instant-count spread)");
  c->add_option("--instant-count", f.o.instant_count, "quasi_static: instants spread over the span from mid-swing")
      ->capture_default_str();
  c->add_option("--dt", f.o.dt, "quasi_static: increment [s] (0: the motion's frame spacing)")->capture_default_str();
  c->add_option("--substeps", f.o.substeps, "dynamic: time steps per frame interval")->capture_default_str();
  c->add_option("--periods", f.o.periods, "dynamic: periods compared at the end of the motion")->capture_default_str();
  c->add_option("--ramp", f.o.ramp, "s (or load level) of ramp from rest before the first frame (0: ten intervals)")
      ->capture_default_str();
  c->add_option("--root-rotation", f.root_rotation,
                "root rotations: fit (root nodes + the rays' tangents at the root), zero (a clamp that does not "
                "turn) or auto (zero with nodal_loads.h5 or --objective static, else fit)")
      ->check(CLI::IsMember({"auto", "fit", "per_ray", "zero"}))
      ->capture_default_str();
  c->add_option("--base", f.base,
                "quasi_static: the base at t carries its stress from the mesh (carried) or is the stress-free "
                "reference of the increment (stress_free)")
      ->check(CLI::IsMember({"carried", "stress_free"}))
      ->capture_default_str();
  c->add_flag("--inertia", f.o.inertia,
              "quasi_static: keep the structure's mass times the motion's measured acceleration as a known load "
              "(eq. (2) with inertia; default: the paper's form without it)");
  c->add_option("--increment", f.increment,
                "quasi_static: newton (the converged increment, Newton from the base), stored (converged too, "
                "from a reference solution on its stored tangent, Newton where that stalls), linear (Newton's "
                "first step from the base's stored tangent: not converged) or hybrid (the optimisers explore "
                "with linear, the polish and intervals use stored; docs/studies/fit_evaluation_speed.md)")
      ->check(CLI::IsMember({"newton", "stored", "linear", "hybrid"}))
      ->capture_default_str();
  c->add_option("--target-noise", f.o.target_noise,
                "a synthetic check: add Gaussian noise of this mean vertex error (fraction of the chord, e.g. "
                "0.003 for fin-track's) to the motion before fitting (0: none)")
      ->capture_default_str();
  c->add_option("--target-noise-seed", f.o.target_noise_seed, "seed of --target-noise")->capture_default_str();
}

const char* const kOwnData =
    "Your own FEM or experiment: write mesh.h5 with the structural datasets only (points, triangles, shell/*, "
    "beams/*, root_nodes; no /ibm), motion.h5 with the measured positions of every mesh node at each time or "
    "load level (time, points), and nodal_loads.h5 with the nodal forces at the same times or levels (time, "
    "nodal_force); `fin-contract --markdown` lists every dataset. Static tests: --objective static (the "
    "model's equilibrium at each level from the unloaded reference; the clamp is the default root); "
    "`fin-fit evaluate` prints the misfit at given moduli before a fit.";

void add_run_command(CLI::App& app, ProblemFlags& flags, RunFlags& r) {
  fit::io::FileFitOptions& o = flags.o;
  auto* rn = app.add_subcommand("run", "fit from stage files (mesh, motion, loads, materials) to materials.h5");
  add_problem_options(rn, flags);
  rn->footer(kOwnData);
  rn->add_option("--out", r.out, "materials.h5 (finverse/materials)")->required();
  rn->add_option("--summary", r.summary, "also write this JSON digest (values, intervals, wall times)");
  rn->add_option("--methods", r.methods, "optimisers, run in this order: ga, cmaes")
      ->delimiter(',')
      ->capture_default_str();
  rn->add_option("--runs", o.fit.runs, "independent seeded runs per method")->capture_default_str();
  rn->add_option("--population", o.fit.population, "GA population (0: 8 per unknown)")->capture_default_str();
  rn->add_option("--generations", o.fit.max_generations, "generation cap per run")->capture_default_str();
  rn->add_option("--stop-tolerance", o.fit.stop_tolerance, "stop when the best objective changes less than this")
      ->capture_default_str();
  rn->add_option("--stop-window", o.fit.stop_window, "... over this many generations")->capture_default_str();
  rn->add_option("--seed", o.fit.seed, "seed of the first run (run k uses seed + k)")->capture_default_str();
  rn->add_flag("--no-polish", r.no_polish, "skip the Levenberg-Marquardt polish (and with it the uncertainty)");
  rn->add_option("--polish-evaluations", o.fit.polish_options.max_evaluations,
                 "evaluation cap of each Levenberg-Marquardt polish (0: 6 (n + 1))")
      ->capture_default_str();
  rn->add_option("--checkpoint", r.checkpoint, "checkpoint file, written after every generation");
  rn->add_flag("--resume", o.fit.resume, "continue from --checkpoint (same inputs and options)");
}

// The parsed flags of run and evaluate into flags.o.
void apply_flags(ProblemFlags& flags, const RunFlags& r) {
  fit::io::FileFitOptions& o = flags.o;
  o.mesh = flags.mesh;
  o.motion = flags.motion;
  o.materials = flags.materials;
  o.out = r.out;
  if (!flags.loads.empty()) o.loads = flags.loads;
  if (!flags.parameters.empty()) o.parameters = flags.parameters;
  if (!r.summary.empty()) o.summary = r.summary;
  if (!r.checkpoint.empty()) o.fit.checkpoint = r.checkpoint;
  o.fit.methods = r.methods;
  o.fit.polish = !r.no_polish;
  if (flags.root_rotation != "auto") o.root_rotation = fem::parse_root_rotation(flags.root_rotation);
  o.stress_free_base = flags.base == "stress_free";
  o.explore_linear = flags.increment == "hybrid";
  o.increment = fit::parse_increment_solve(o.explore_linear ? "stored" : flags.increment);
}

}  // namespace finverse::apps
