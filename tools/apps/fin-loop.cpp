// fin-loop: closing the loop (issue 34, DESIGN.md section 5.6). Exit 0 on success, 2 on bad input
// (one line; nothing written); flap: 1 when a graded metric of its summary misses.
//   fin-loop residual --mesh mesh.h5 --reconstruction motion.h5 --prediction fsi.h5
//       --out residual.h5 [--summary residual.json] [--period T]
//   fin-loop trace --mesh mesh.h5 --motion motion.h5 --loads loads.h5 --materials materials.json
//       [--fit materials.h5] --out loop.h5 [--summary loop.json] [--candidates effects.json]
//       [--parameters E_membrane,nu] [--frequency f] [--fit-drive K] [--drive-harmonics H]
//   fin-loop flap --reference hessenthaler2017.json --fit fit/summary.json [--plane plane/summary.json]
//       --out-dir DIR [--name N]   (issue 34 validation 2 (iii): the Hessenthaler flap's tips)
//   fin-loop flap ... --phase1 flap_loads.h5 --centreline phaseI_centreline.csv
//       [--phase1-viscosity v/flap_loads.h5] [--phase1-inflow u/flap_loads.h5]   (issue 49: centrelines)
// Its own executable rather than a mode of fin-fit: it reads a prediction (fsi.h5 or a fin-fem
// response) that fin-fit never sees, writes its own stage files (residual.h5, loop.h5), and
// links the candidate effects and the residual analysis that the fit itself does not need; the
// refit it runs is fin-fit's Levenberg-Marquardt, called as a library. `flap` is the same tracer
// on measured scalar data (loop/flap_loop.hpp), so it lives here rather than in fin-fit.
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/cli.hpp"
#include "core/summary.hpp"
#include "loop/errors.hpp"
#include "loop/flap_loop.hpp"
#include "loop/io/file_loop.hpp"

int main(int argc, char** argv) {
  CLI::App app{"fin-loop: the residual between model and reconstruction, and the effect that explains it"};
  finverse::cli::Standard standard(app, "fin-loop");
  app.require_subcommand(1);

  finverse::loop::io::FileResidualOptions ro;
  std::string mesh, recon, prediction, out, summary;
  double period = 0;
  auto* rs = app.add_subcommand("residual", "prediction - reconstruction: cycle mean, harmonics, POD modes");
  rs->add_option("--mesh", mesh, "mesh.h5 (finverse/mesh)")->required();
  rs->add_option("--reconstruction", recon, "motion.h5: the reconstruction on the mesh's nodes")->required();
  rs->add_option("--prediction", prediction, "fsi.h5, or fin-fem run's motion-schema output")->required();
  rs->add_option("--out", out, "residual.h5 (finverse/residual)")->required();
  rs->add_option("--summary", summary, "also write this JSON digest");
  rs->add_option("--period", period, "beat period T [s] (0: motion.h5's, else the prediction's T)")
      ->capture_default_str();
  rs->add_option("--harmonics", ro.harmonics, "harmonics of the beat frequency")->capture_default_str();
  rs->add_option("--modes", ro.modes, "POD modes kept")->capture_default_str();

  finverse::loop::io::FileTraceOptions to;
  std::string motion, loads, materials, fit, candidates, root_rotation = "fit";
  double frequency = 0;
  auto* tr = app.add_subcommand("trace", "rank candidate effects by a score test, add, refit, keep while BIC and "
                                         "held-out error improve");
  tr->add_option("--mesh", mesh, "mesh.h5 (finverse/mesh)")->required();
  tr->add_option("--motion", motion, "motion.h5: the reconstruction; its root nodes drive the model")->required();
  tr->add_option("--loads", loads, "loads.h5: the measured hydrodynamic loads");
  tr->add_option("--materials", materials, "materials JSON of the fit (densities, parameters not fitted)")->required();
  tr->add_option("--fit", fit, "materials.h5 of fin-fit (best values and bounds); none: the default fin "
                               "parameters at the --materials values (a twin's start)");
  tr->add_option("--out", out, "loop.h5 (finverse/loop)")->required();
  tr->add_option("--summary", summary, "also write this JSON digest");
  tr->add_option("--candidates", candidates, "JSON array of effect specs (default: every effect, group all)");
  tr->add_option("--parameters", to.parameters, "refitted subset of the fit's parameters (default: all)")
      ->delimiter(',');
  tr->add_option("--fit-drive", to.drive_order,
                 "order K of the root drive's correction refitted with the moduli: K Legendre terms over the "
                 "rays for the pitch's sine and cosine parts, and the heave's (0: the tracked drive held)")
      ->check(CLI::Range(0, 20))
      ->capture_default_str();
  tr->add_option("--drive-harmonics", to.drive_harmonics,
                 "read the root drive off the reconstruction through this many harmonics of the beat (0: as tracked)")
      ->check(CLI::Range(0, 16))
      ->capture_default_str();
  tr->add_option("--frequency", frequency, "beat frequency [Hz] (0: 1 / motion.h5 T)")->capture_default_str();
  tr->add_option("--period", period, "period for the held-out cycles [s] (0: motion.h5 T)")->capture_default_str();
  std::string analysis = "quasi_static", root_motion;
  tr->add_option("--analysis", analysis, "model runs: quasi_static (fin-fem run's default) or dynamic")
      ->check(CLI::IsMember({"quasi_static", "dynamic"}))
      ->capture_default_str();
  tr->add_option("--root-motion", root_motion, "motion.h5 whose root nodes drive the model (default: --motion)");
  tr->add_option("--substeps", to.substeps, "dynamic: time steps per frame interval")->capture_default_str();
  tr->add_option("--spectral-radius", to.spectral_radius, "dynamic: generalized-alpha rho_inf")->capture_default_str();
  tr->add_flag("--full-newton", to.full_newton,
               "dynamic: each step's Newton starts where the last ended and refactorises every iteration (the "
               "thin fin needs it, with --spectral-radius 0.5; docs/studies/fin_dynamic_run.md)");
  tr->add_option("--ramp", to.ramp, "s of ramp from rest before the first frame (0: ten frame intervals)")
      ->capture_default_str();
  tr->add_option("--root-rotation", root_rotation, "root rotations: fit, per_ray or zero")->capture_default_str();
  tr->add_option("--max-effects", to.max_effects, "effects added at most")->capture_default_str();
  tr->add_option("--alpha", to.alpha, "family-wise level of the score test")->capture_default_str();
  tr->add_option("--relative-step", to.relative_step, "score finite-difference step, fraction of a parameter's range")
      ->capture_default_str();
  tr->add_option("--lm-evaluations", to.lm.max_evaluations, "evaluation cap of each refit (0: 6 (n + 1))")
      ->capture_default_str();
  bool no_base_refit = false;
  tr->add_flag("--no-base-refit", no_base_refit, "rank at the fit's values without first refitting the base");

  finverse::loop::FlapLoopOptions fo;
  std::string plane, phase1, phase1_viscosity, phase1_inflow, centreline, out_dir = "results/validation";
  auto* fl = app.add_subcommand("flap", "the tracer on the Hessenthaler (2017) flap's measured tips (issue 34)");
  fl->add_option("--reference", fo.reference, "hessenthaler2017.json")->required();
  fl->add_option("--fit", fo.fit_summary, "fin-fit flap's summary.json (E; its metrics are carried)")->required();
  fl->add_option("--plane", plane, "fin-fsi hessenthaler_plane's summary.json: its mean flow load as Phase I's");
  fl->add_option("--phase1", phase1, "fin-fsi flap --loads of the 3-D Phase I run: centreline frames (issue 49)");
  fl->add_option("--phase1-viscosity", phase1_viscosity, "the same run with --viscosity-factor: viscosity_error");
  fl->add_option("--phase1-inflow", phase1_inflow, "the same run with --inflow-factor: inflow_error");
  fl->add_option("--centreline", centreline, "the MRI centreline (phaseI_centreline.csv), with --phase1");
  fl->add_option("--along", fo.mesh.along, "shell cells along the flap")->capture_default_str();
  fl->add_option("--across", fo.mesh.across, "shell cells across the flap")->capture_default_str();
  fl->add_option("--alpha", fo.alpha, "family-wise level of the score test")->capture_default_str();
  fl->add_option("--out-dir", out_dir, "directory that receives <name>/summary.json")->capture_default_str();
  fl->add_option("--name", fo.name, "case name")->capture_default_str();

  return finverse::cli::run(app, standard, argc, argv, [&]() -> int {
    if (*fl) {
      if (!plane.empty()) fo.plane_summary = plane;
      if (!phase1.empty()) fo.phase1_loads = phase1;
      if (!phase1_viscosity.empty()) fo.phase1_viscosity = phase1_viscosity;
      if (!phase1_inflow.empty()) fo.phase1_inflow = phase1_inflow;
      if (!centreline.empty()) fo.centreline = centreline;
      if ((fo.phase1_viscosity || fo.phase1_inflow) && !fo.phase1_loads)
        throw finverse::loop::InvalidInput("fin-loop flap: --phase1-viscosity and --phase1-inflow need --phase1");
      fo.progress = [](const std::string& line) { std::cerr << "fin-loop flap: " << line << "\n"; };
      const finverse::Summary summary = finverse::loop::run_flap_loop(fo);
      const auto path = std::filesystem::path(out_dir) / fo.name / "summary.json";
      std::filesystem::create_directories(path.parent_path());
      summary.write(path);
      std::cerr << "fin-loop flap: wrote " << path.string() << "\n";
      return summary.pass() ? 0 : 1;
    }
    if (*rs) {
      ro.mesh = mesh;
      ro.reconstruction = recon;
      ro.prediction = prediction;
      ro.out = out;
      if (!summary.empty()) ro.summary = summary;
      if (period > 0) ro.period = period;
      const auto a = finverse::loop::io::run_residual_from_files(ro, finverse::cli::effective_config(app));
      std::cerr << "fin-loop residual: RMS " << a.rms << " m, trailing edge " << a.trailing_edge.rms << " m ("
                << a.trailing_edge.relative << " of its excursion), wrote " << out << "\n";
      return 0;
    }
    to.mesh = mesh;
    to.motion = motion;
    to.materials = materials;
    if (!fit.empty()) to.fit = fit;
    to.out = out;
    if (!loads.empty()) to.loads = loads;
    if (!root_motion.empty()) to.root_motion = root_motion;
    to.analysis = finverse::fem::parse_analysis(analysis);
    if (!candidates.empty()) to.candidates = candidates;
    if (!summary.empty()) to.summary = summary;
    if (frequency > 0) to.frequency = frequency;
    if (period > 0) to.period = period;
    to.root_rotation = finverse::fem::parse_root_rotation(root_rotation);
    to.refit_base = !no_base_refit;
    to.lm.threads = finverse::cli::threads_in_use();
    const auto rec = finverse::loop::io::run_trace_from_files(to, finverse::cli::effective_config(app));
    std::cerr << "fin-loop trace: added " << rec.result.added.size() << " effect(s) (" << rec.result.stop_reason
              << "), " << rec.result.evaluations << " model runs, wrote " << out << "\n";
    return 0;
  });
}
