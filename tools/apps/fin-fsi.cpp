// fin-fsi: coupled flow-structure runs (issue 32; DESIGN.md 5.3). Parses flags, calls the library
// (tools/fsi/validation), writes fsi.h5 and summary.json. Exit 0 when every graded metric passes,
// 1 when one misses, 2 on error (bad input, a diverged coupling naming the step).
//
//   fin-fsi turek_hron --case FSI1 --reference data/reference/turek_hron.json
//       --acceleration iqn-ils --cells-per-diameter 16 --out fsi.h5 --summary summary.json
//       [--checkpoint ckpt.h5 --checkpoint-every N] [--restart ckpt.h5 [--restart-new-coupling]]
#include <fstream>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "core/cli.hpp"
#include "core/summary.hpp"
#include "core/summary_print.hpp"
#include "fsi/validation/pitching_plate_fsi.hpp"
#include "fsi/validation/seed_table1.hpp"
#include "fsi/validation/turek_hron_fsi.hpp"

namespace {

namespace fv = finverse::fsi::validation;

// fin-fsi turek_hron: the 2-D flag behind the cylinder (FSI1, FSI2, FSI3). One block per
// subcommand: its options, then what it runs.
struct TurekHronCommand {
  fv::TurekHronFsiOptions o;
  std::string reference, out, summary_path;
  bool strict = false;
  bool iterations = false;
  CLI::App* th = nullptr;

  void add(CLI::App& app) {
    th = app.add_subcommand("turek_hron", "Turek-Hron FSI1 (steady), FSI2, FSI3 (periodic)");
    th->add_option("--case", o.case_name, "FSI1, FSI2 or FSI3")->capture_default_str();
    th->add_option("--reference", reference, "turek_hron.json")->required();
    th->add_option("--acceleration", o.acceleration, "aitken, iqn-ils or constant")->capture_default_str();
    th->add_option("--omega", o.omega, "omega0 (aitken, iqn-ils) or omega (constant)")->capture_default_str();
    th->add_option("--tolerance", o.tolerance, "relative interface displacement residual")->capture_default_str();
    th->add_option("--absolute-tolerance", o.absolute_tolerance, "... or interface displacement change [m]")
        ->capture_default_str();
    th->add_option("--max-iterations", o.max_iterations, "coupling iterations per step")->capture_default_str();
    th->add_option("--cells-per-diameter", o.cells_per_diameter, "flow grid: D / h in the box")->capture_default_str();
    th->add_option("--core-cells-per-diameter", o.core_cells_per_diameter, "finer core around the body: D / h_core")
        ->capture_default_str();
    th->add_option("--core-wake", o.core_wake, "the core ends this many D behind the tip")->capture_default_str();
    th->add_option("--wake-box", o.wake_box, "uniform box behind the tip [D]")->capture_default_str();
    th->add_option("--stretch-ratio", o.stretch_ratio, "largest neighbouring cell-width ratio outside the box")
        ->capture_default_str();
    th->add_option("--wall-stretch-ratio", o.wall_stretch_ratio, "the same towards the channel walls; 0: --stretch-ratio")
        ->capture_default_str();
    th->add_option("--channel-length", o.channel_length, "channel length [m] (< 2.5: tests only)")
        ->capture_default_str();
    th->add_option("--ramp-time", o.ramp_time, "inflow ramp time [s]")->capture_default_str();
    th->add_option("--circle-vertices", o.circle_vertices, "cylinder polygon resolution")->capture_default_str();
    th->add_option("--nx", o.mesh.nx, "Q9 elements along the flag")->capture_default_str();
    th->add_option("--ny", o.mesh.ny, "Q9 elements across the flag")->capture_default_str();
    th->add_option("--dt", o.dt, "time step [s]; 0: cfl h / U_max")->capture_default_str();
    th->add_option("--cfl", o.cfl, "CFL number for the default dt")->capture_default_str();
    th->add_option("--t-end", o.t_end, "simulated time [s]; 0: the case's default")->capture_default_str();
    th->add_option("--spectral-radius", o.spectral_radius, "structure's generalized-alpha rho_inf")
        ->capture_default_str();
    th->add_option("--substeps", o.structure_substeps, "structure sub-steps per step")->capture_default_str();
    th->add_option("--output-every", o.output_every, "fsi.h5 frame every k steps")->capture_default_str();
    th->add_option("--out", out, "fsi.h5 to write (optional)");
    th->add_option("--summary", summary_path, "summary.json to write")->required();
    th->add_option("--divergence-iterations", o.divergence_iterations,
                   "residual growing this many iterations in a row: diverged (0: off)")
        ->capture_default_str();
    th->add_option("--checkpoint", o.checkpoint, "checkpoint file (replaced atomically) for --restart");
    th->add_option("--checkpoint-every", o.checkpoint_every, "checkpoint every N steps (0: after the last only)")
        ->capture_default_str();
    th->add_option("--restart", o.restart, "continue from this checkpoint (same options; t_end may grow)")
        ->check(CLI::ExistingFile);
    th->add_flag("--restart-new-coupling", o.restart_new_coupling,
                 "the restart may change acceleration, omega, tolerances and caps (drops the carried history)");
    th->add_option("--paraview", o.paraview_dir, "ParaView series (structure.pvd, flow.pvd) into this directory");
    th->add_option("--paraview-every", o.paraview_every, "ParaView frame every k-th fsi.h5 frame")
        ->capture_default_str();
    th->add_flag("--hold-flag-rigid", o.hold_flag_rigid,
                 "benchmark: from --restart on, the flow alone with the flag frozen (wall time per step)");
    th->add_flag("--strict", strict, "stop at the iteration cap (default: accept the best iterate)");
    th->add_flag("--iterations", iterations, "a progress line per coupling iteration too");
  }

  int run() {
    o.reference = reference;
    o.fsi_h5 = out;
    o.progress = [](const std::string& line) { std::cerr << line << "\n"; };
    o.progress_iterations = iterations;
    o.accept_at_cap = !strict;
    fv::TurekHronFsiRun run = fv::run_turek_hron_fsi(o);
    finverse::Summary& s = run.summary;
    s.set_timing(run.wall_seconds, finverse::cli::threads_in_use());
    s.write(summary_path);
    finverse::print_metrics(s, std::cerr);
    std::ifstream reference_file(reference);
    for (const auto& line : fv::seed_table1_lines(nlohmann::json::parse(reference_file), o.case_name, s))
      std::cerr << line << "\n";
    std::cerr << "fin-fsi turek_hron " << o.case_name << ": " << (s.pass() ? "pass" : "missed") << ", "
              << run.wall_seconds << " s, wrote " << summary_path << "\n";
    return s.pass() ? 0 : 1;
  }
};

// fin-fsi pitching_plate: the 3-D flexible plate pitching about its leading edge (seed sec. 3.2),
// every K of --K in one run (and --rigid), one summary.json.
struct PitchingPlateCommand {
  fv::PitchingPlateOptions o;
  std::string summary_path;
  CLI::App* pp = nullptr;

  void add(CLI::App& app) {
    pp = app.add_subcommand("pitching_plate", "flexible plate pitching in a stream (W/L 0.54, 12 deg, f = 1)");
    pp->add_option("--K", o.stiffness, "bending stiffnesses D / (rho_f U^2 L^3), comma-separated")
        ->delimiter(',')
        ->capture_default_str();
    pp->add_flag("--rigid", o.rigid, "also run the rigid plate (prescribed pitching)");
    pp->add_option("--re", o.re, "Reynolds number U L / nu")->capture_default_str();
    pp->add_option("--mass-ratio", o.mass_ratio, "rho_s h / (rho_f L)")->capture_default_str();
    pp->add_option("--nx", o.nx, "shell cells along the chord")->capture_default_str();
    pp->add_option("--nz", o.nz, "shell cells along the span (even)")->capture_default_str();
    pp->add_option("--cells-per-chord", o.cells_per_chord, "flow grid: L / h around the plate")->capture_default_str();
    pp->add_option("--thickness-cells", o.thickness_cells, "closed thin body thickness [h]")->capture_default_str();
    pp->add_option("--stretch-ratio", o.stretch_ratio, "cell-width ratio outside the uniform box")
        ->capture_default_str();
    pp->add_option("--downstream", o.downstream, "domain length behind the trailing edge [L]")->capture_default_str();
    pp->add_option("--half-height", o.half_height, "domain half height (y) [L]")->capture_default_str();
    pp->add_option("--half-width", o.half_width, "domain half width (z) [L]")->capture_default_str();
    pp->add_option("--steps-per-period", o.steps_per_period, "time steps per pitching period")->capture_default_str();
    pp->add_option("--periods", o.periods, "periods to run (the last one is measured)")->capture_default_str();
    pp->add_option("--ramp-periods", o.ramp_periods, "periods of the smooth start")->capture_default_str();
    pp->add_option("--acceleration", o.acceleration, "aitken, iqn-ils or constant")->capture_default_str();
    pp->add_option("--omega", o.omega, "omega0 (aitken, iqn-ils) or omega (constant)")->capture_default_str();
    pp->add_option("--tolerance", o.tolerance, "relative interface displacement residual")->capture_default_str();
    pp->add_option("--absolute-tolerance", o.absolute_tolerance, "... or interface displacement change [L]")
        ->capture_default_str();
    pp->add_option("--max-iterations", o.max_iterations, "coupling iterations per step (then the best iterate)")
        ->capture_default_str();
    pp->add_option("--structure-tolerance", o.structure_tolerance, "shell Newton residual tolerance")
        ->capture_default_str();
    pp->add_option("--summary", summary_path, "summary.json to write")->required();
  }

  int run() {
    o.progress = [](const std::string& line) { std::cerr << line << "\n"; };
    fv::PitchingPlateRun run = fv::run_pitching_plate(o);
    finverse::Summary& s = run.summary;
    s.set_timing(run.wall_seconds, finverse::cli::threads_in_use());
    s.write(summary_path);
    finverse::print_metrics(s, std::cerr);
    std::cerr << "fin-fsi pitching_plate: " << (s.pass() ? "pass" : "missed") << ", " << run.wall_seconds
              << " s, wrote " << summary_path << "\n";
    return s.pass() ? 0 : 1;
  }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fin-fsi: implicit partitioned flow-structure coupling (Aitken, IQN-ILS)"};
  finverse::cli::Standard standard(app, "fin-fsi");
  app.require_subcommand(1);
  TurekHronCommand turek_hron;
  turek_hron.add(app);
  PitchingPlateCommand pitching_plate;
  pitching_plate.add(app);
  return finverse::cli::run(app, standard, argc, argv, [&]() -> int {
    if (turek_hron.th->parsed()) return turek_hron.run();
    if (pitching_plate.pp->parsed()) return pitching_plate.run();
    return 2;
  });
}
