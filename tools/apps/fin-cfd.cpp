// fin-cfd: the incompressible Navier-Stokes solver (DESIGN.md sections 5.1, 6): its validation cases,
// a case file, and the fin's prescribed-motion loads.
//
//   fin-cfd taylor_green [--coarse]                  a validation case (fin-cfd --help lists them;
//   fin-cfd dfg_2d2 --cells-per-diameter 32          fin-cfd <case> --help lists its options)
//   fin-cfd fin --mesh mesh.h5 --motion motion.h5 --out loads.h5 [--reynolds 1000] ...
//   mpirun -n 4 fin-cfd --threads 1 fin ...   the pressure solve over 4 ranks, each holding the whole
//                                             flow (cfd/parallel/rank_pressure_system.hpp); the same
//                                             loads.h5 as one process
//   fin-cfd thin_plate --mesh plate_mesh.h5 --motion plate_motion.h5
//   fin-cfd thin_surface_bench --out results/bench/thin_surface.json   a thin body's step cost
//   fin-cfd [--coarse] run data/cases/cfd/dfg_2d2.yaml [--t-end 2]     a case file (cases/case_file.hpp):
//   fin-cfd run data/cases/cfd/sphere_re100_stl.yaml                   a validation case or a user's flow
//
// Cases and grading: tools/cfd/validation (cases.hpp); the fin run: tools/cfd/io. Each case writes
// <out-dir>/<case>/summary.json; exit 1 when a graded metric misses its tolerance, 2 on an error.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "cfd/cases/run_case_file.hpp"
#include "cfd/io/fin_flow_case.hpp"
#include "cfd/io/fin_input.hpp"
#include "cfd/io/fin_run_log.hpp"
#include "cfd/io/flow_snapshots.hpp"
#include "cfd/validation/cases.hpp"
#include "cfd/validation/fin_loads_check.hpp"
#include "cfd/validation/thin_plate_case.hpp"
#include "cfd/validation/thin_surface_bench.hpp"
#include "core/cli.hpp"
#include "flow_ranks_launch.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/stage_files.hpp"


namespace {

using namespace finverse;
namespace fs = std::filesystem;
namespace val = finverse::cfd::validation;

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

// fin-cfd fin: mesh.h5 + motion.h5 -> the prescribed-motion flow -> loads.h5 (tools/cfd/io).
struct FinArgs {
  fs::path mesh, motion, out, summary, checkpoint, restart;
  cfd::io::FinFlowOptions flow;
  long checkpoint_every = 0, snapshot_every = 0;
};

int run_fin(const FinArgs& a, const CLI::App& app) {
  const auto in = cfd::io::read_fin_input(a.mesh, a.motion, a.flow.motion_harmonics);
  cfd::io::log_fin_input(in, a.mesh, a.motion);
  cfd::io::FinFlowStats st;
  cfd::io::FinCheckpointing ck;
  // On MPI ranks every rank runs the whole flow and rank 0 alone writes files.
  const bool writer = cli::mpi_launch_rank() == 0;
  ck.every = a.checkpoint_every;
  ck.write = writer;
  ck.file = !a.checkpoint.empty() ? a.checkpoint : a.out.parent_path() / (a.out.stem().string() + ".checkpoint.h5");
  ck.restart = a.restart;
  cfd::io::FlowSnapshots snapshots(a.out.parent_path() / (a.out.stem().string() + ".flow.pvd"), writer ? a.snapshot_every : 0,
                                   !ck.restart.empty());
  if (a.snapshot_every > 0)
    ck.at_output = [&](long output, double t, const cfd::FlowSolver& s) {
      if (writer) snapshots.at_output(output, t, st.dt, s);
    };
  if (!ck.restart.empty()) log::info("restarting from " + ck.restart.string());
  cfd::io::FinProgress progress;
  stage::Loads loads = cfd::io::run_fin_flow(in, a.flow, st, std::ref(progress), ck);
  progress.finish(st.t_end);
  if (!writer) return kExitOk;
  if (snapshots.size())
    log::info("wrote " + std::to_string(snapshots.size()) + " flow snapshots to " + snapshots.pvd().string());
  cfd::io::log_fin_run(in, st, ck.file);
  const auto& g = st.grid;
  Provenance prov{"fin-cfd", cli::effective_config(app), {a.mesh, a.motion}};
  prov.config["achieved"] = {{"grid", {g.nx(), g.ny(), g.nz()}},
                             {"h", st.h},
                             {"dt", st.dt},
                             {"steps", st.steps},
                             {"U", st.U},
                             {"nu", st.nu},
                             {"chord", st.chord},
                             {"t_begin", st.t_begin},
                             {"t_end", st.t_end}};
  stage::write(a.out, loads, prov);
  log::info("wrote " + a.out.string() + " (" + std::to_string(loads.time.size()) + " output times)");
  if (a.summary.empty()) return kExitOk;
  // Validation: re-read what was written; the nodal loads must sum to the integrated force.
  const std::string name = a.summary.parent_path().filename().string();
  Summary s = val::fin_loads_summary(name.empty() ? "fin_loads" : name,
                                     a.mesh.filename().string() + " + " + a.motion.filename().string(),
                                     stage::read<stage::Loads>(a.out), st, in.motion->body().thickness, prov.config);
  s.set_timing(st.wall_seconds, cli::threads_in_use());
  s.write(a.summary);
  log::info("wrote " + a.summary.string() + (s.pass() ? " (all metrics pass)" : " (a metric FAILED)"));
  return s.pass() ? kExitOk : kExitDifferent;
}

void add_fin_options(CLI::App* f, FinArgs& a) {
  auto& o = a.flow;
  f->add_option("--mesh", a.mesh, "mesh.h5 (fin-mesh)")->required()->check(CLI::ExistingFile);
  f->add_option("--motion", a.motion, "motion.h5 (fin-mesh)")->required()->check(CLI::ExistingFile);
  f->add_option("--out", a.out, "output loads.h5")->required();
  f->add_option("--summary", a.summary, "also write a validation summary.json (nodal loads sum check)");
  for (const auto& n : cfd::io::fin_flow_flags(o)) f->add_option(n.flag, *n.value, n.help)->capture_default_str();
  f->add_flag("--staircase-balance{false}", o.cut_cells,
              "mass balance: close the faces of every non-fluid cell, moving with the wall (the staircase "
              "balance), instead of the cut-cell one (Seo & Mittal 2011; on the default fin 2.3x less noise in "
              "the lateral force)");
  f->add_flag("--sample-loads", o.sample_loads,
              "loads at an output time: the one step on it instead of the mean over the output interval centred "
              "on it (docs/studies/fin_load_noise.md)");
  f->add_option("--surface", o.surface,
                "how the flow sees the fin: closed (the closed thin body of mesh.h5 /ibm, ghost cells) or sheet (the "
                "mid-surface as a zero-thickness immersed surface, docs/studies/thin_surface.md)")
      ->capture_default_str()
      ->check(CLI::IsMember({"closed", "sheet"}));
  f->add_option("--kernel", o.kernel, "sheet: regularized delta kernel (roma3, peskin4, smooth3, smooth4)")
      ->capture_default_str()
      ->check(CLI::IsMember({"roma3", "peskin4", "smooth3", "smooth4"}));
  f->add_option("--marker-spacing", o.marker_spacing, "sheet: marker spacing in core cell widths")
      ->capture_default_str()
      ->check(CLI::Range(0.25, 4.0));
  f->add_flag("--raw-sheet-force", o.raw_sheet_force,
              "sheet: the markers' impulses as the loads, without removing the inertia of the fluid band the kernel "
              "moves with the sheet (docs/studies/thin_surface.md)");
  f->add_flag("--sheet-loads-mean", o.sheet_loads_mean,
              "sheet: loads at an output time are the mean over the output interval centred on it instead of the "
              "raw force of the step on it");
  f->add_option("--motion-harmonics", o.motion_harmonics,
                "keep a periodic motion to its first K harmonics (0: as sampled); the tracked motion's frame-rate "
                "noise is acceleration a sheet feels as force")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000));
  f->add_option("--checkpoint-every", a.checkpoint_every, "write a checkpoint every N steps (0: never)")
      ->capture_default_str();
  f->add_option("--checkpoint", a.checkpoint, "checkpoint file (default: <out stem>.checkpoint.h5 next to --out)");
  f->add_option("--restart", a.restart, "continue from this checkpoint (same inputs and options)")
      ->check(CLI::ExistingFile);
  f->add_option("--snapshot-every", a.snapshot_every,
                "write the flow field (velocity, pressure, vorticity, lambda2) every N-th output time to "
                "<out stem>.flow.pvd (ParaView; 0: never)")
      ->capture_default_str()
      ->check(finverse::cli::non_negative());
}

// fin-cfd thin_plate: the heaving and pitching rigid plate of the thin_plate_loads case as stage files.
struct PlateArgs {
  fs::path mesh, motion;
  double thickness = 0.1;  // / chord
  int frames = 40;
};

int run_plate(const PlateArgs& a, const CLI::App& app, bool coarse) {
  cfd::io::ThinPlateSetup p;
  p.thickness = a.thickness * p.chord;
  p.frames = a.frames;
  if (coarse) {
    p.nx = 6;
    p.nz = 8;
  }
  auto files = cfd::io::make_thin_plate(p);
  Provenance prov{"fin-cfd", cli::effective_config(app), {}};
  prov.config["plate"] = cfd::io::describe(p);
  stage::write(a.mesh, files.mesh, prov);
  stage::write(a.motion, files.motion, prov);
  log::info("thin plate " + fmt("%.3g m", p.chord) + " x " + fmt("%.3g m", p.span) + ", " +
            std::to_string(files.mesh.points.dim(0)) + " nodes, heave " + fmt("%.3g m", p.heave) + ", pitch " +
            fmt("%.3g rad", p.pitch) + ", T " + fmt("%.3g s", p.period) + ": wrote " + a.mesh.string() + ", " +
            a.motion.string());
  return kExitOk;
}

// fin-cfd thin_surface_bench: a step of the plate as a sheet and as the closed body against the
// same grid with no body (thin_surface_bench.hpp); results/bench/thin_surface.json.
struct BenchArgs {
  fs::path out;
  double periods = 0.25;
  int cells_per_chord = 20;
};

int run_thin_surface_bench(const BenchArgs& a, bool coarse) {
  const auto b = val::run_thin_surface_bench(coarse ? 0.05 : a.periods, coarse ? 10 : a.cells_per_chord);
  Summary s("bench", "thin_surface",
            "time step of the heaving/pitching plate (thin_plate_loads, Re 100) as a zero-thickness sheet and as the "
            "closed two-cell body against the same grid and step with no body, one run");
  const double sheet = b.sheet_s_per_step / b.empty_s_per_step, closed = b.closed_s_per_step / b.empty_s_per_step;
  if (coarse)
    s.info("sheet_step_over_empty_step", sheet);
  else
    s.at_most("sheet_step_over_empty_step", sheet, 1.2, "issue 44 benchmark: a flow step with the fin <= 1.2x no body");
  s.info("closed_step_over_empty_step", closed);
  s.info("sheet_seconds_per_step", b.sheet_s_per_step, "s");
  s.info("closed_seconds_per_step", b.closed_s_per_step, "s");
  s.info("empty_seconds_per_step", b.empty_s_per_step, "s");
  s.info("steps", static_cast<double>(b.steps));
  s.info("cells", static_cast<double>(b.cells));
  s.parameters() = {
      {"periods", coarse ? 0.05 : a.periods}, {"cells_per_chord", coarse ? 10 : a.cells_per_chord}, {"coarse", coarse}};
  s.set_timing(0, cli::threads_in_use());
  s.write(a.out);
  log::info("thin surface bench: step with the sheet " + fmt("%.3g", sheet) + "x, closed body " + fmt("%.3g", closed) +
            "x the step with no body (" + std::to_string(b.cells) + " cells, " + std::to_string(b.steps) + " steps)");
  return s.pass() ? kExitOk : kExitDifferent;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fin-cfd: incompressible Navier-Stokes solver (fractional step, collocated, stretched grid)"};
  cli::Standard standard(app, "fin-cfd");
  standard.mpi = true;  // fin-cfd fin; the other subcommands refuse ranks below
  app.require_subcommand(1);
  // A flag given twice takes its last value: a case file's options, then the command line's.
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  val::CaseOptions options;
  std::string out_dir = options.out_dir.string();
  app.add_option("--out-dir", out_dir, "directory that receives <case>/summary.json")->capture_default_str();
  app.add_flag("--coarse", options.coarse, "the coarse (CI) variant of the case");
  std::vector<std::pair<CLI::App*, const val::ValidationCase*>> subcommands;
  for (const val::ValidationCase& c : val::validation_cases()) {
    CLI::App* sc = app.add_subcommand(c.name, c.description);
    val::add_case_flags(sc, val::case_options(c, options));
    subcommands.emplace_back(sc, &c);
  }
  FinArgs fin_args;
  auto* fin = app.add_subcommand("fin", "prescribed-motion flow around the fin (mesh.h5 + motion.h5) -> loads.h5");
  add_fin_options(fin, fin_args);
  PlateArgs plate_args;
  auto* plate = app.add_subcommand("thin_plate", "heaving and pitching rigid thin plate as mesh.h5 + motion.h5");
  plate->add_option("--mesh", plate_args.mesh, "output mesh.h5")->required();
  plate->add_option("--motion", plate_args.motion, "output motion.h5")->required();
  plate->add_option("--thickness", plate_args.thickness, "closed-body thickness / chord")->capture_default_str();
  plate->add_option("--frames", plate_args.frames, "samples per period")->capture_default_str();
  BenchArgs bench_args;
  auto* bench = app.add_subcommand("thin_surface_bench", "a thin body's step cost: sheet and closed body vs no body");
  bench->add_option("--out", bench_args.out, "output JSON (results/bench/thin_surface.json)")->required();
  bench->add_option("--periods", bench_args.periods, "plate periods timed")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 10.0));
  bench->add_option("--cells-per-chord", bench_args.cells_per_chord, "h = c / N")
      ->capture_default_str()
      ->check(CLI::Range(8, 200));
  fs::path case_file;
  auto* run = app.add_subcommand("run", "a case file: a validation case or a user's flow (data/cases/cfd/README.md)");
  run->add_option("file", case_file, "the case file (YAML)")->required()->check(CLI::ExistingFile);
  std::vector<std::string> args;
  try {
    args = cfd::cases::expand_case_file(std::vector<std::string>(argv, argv + argc),
                                        [&](const std::string& name) -> std::optional<std::vector<std::string>> {
                                          if (name != "fin" && !val::find_case(name)) return std::nullopt;
                                          std::vector<std::string> flags;
                                          for (const CLI::Option* o : app.get_subcommand(name)->get_options())
                                            for (const std::string& l : o->get_lnames()) flags.push_back("--" + l);
                                          return flags;
                                        });
  } catch (const std::exception& e) {
    log::error(e.what());
    return kExitError;
  }
  std::vector<char*> argv2;
  for (std::string& a : args) argv2.push_back(a.data());
  return cli::run(app, standard, static_cast<int>(argv2.size()), argv2.data(), [&]() -> int {
    if (*fin) return on_flow_ranks("fin-cfd", [&] { return run_fin(fin_args, app); });
    if (cli::mpi_launch_size() > 1)
      throw Error("fin-cfd " + app.get_subcommands().front()->get_name() +
                  " does not run on MPI ranks (fin-cfd fin does); run it without mpirun");
    if (*run) return cfd::cases::run_flow_case_file(case_file, options.coarse, out_dir);
    if (*plate) return run_plate(plate_args, app, options.coarse);
    if (*bench) return run_thin_surface_bench(bench_args, options.coarse);
    options.out_dir = out_dir;
    for (const auto& [sc, c] : subcommands)
      if (*sc) return val::run_case(*c, options);
    return kExitError;
  });
}
