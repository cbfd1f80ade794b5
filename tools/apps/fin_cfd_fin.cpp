// fin-cfd fin and fin-cfd thin_plate (see fin_cfd_fin.hpp): flags to the library
// (tools/cfd/io: fin_input, fin_flow_case, loads_record, thin_plate_case) and back to files.
#include "fin_cfd_fin.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "cfd/io/fin_flow_case.hpp"
#include "cfd/io/fin_input.hpp"
#include "cfd/io/loads_record.hpp"
#include "cfd/validation/thin_plate_case.hpp"
#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/stage_files.hpp"
#include "core/summary.hpp"
#include "core/vtk_output.hpp"

namespace finverse::fin_cfd {

namespace fs = std::filesystem;

struct FinCommands {
  CLI::App* fin = nullptr;
  CLI::App* plate = nullptr;
  fs::path mesh, motion, out, summary;
  cfd::io::FinFlowOptions flow;
  long checkpoint_every = 0;
  fs::path checkpoint, restart;
  long snapshot_every = 0;
  fs::path plate_mesh, plate_motion;
  double plate_thickness = 0.1;  // / chord
  int plate_frames = 40;
};

namespace {

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

int run_fin(const FinCommands& c, const CLI::App& app) {
  const auto in = cfd::io::read_fin_input(c.mesh, c.motion);
  log::info(c.mesh.string() + ": " + std::to_string(in.rest.size()) + " nodes, " +
            std::to_string(in.mid_triangles.size()) + " shell triangles; closed thin body " +
            std::to_string(in.motion->body().source_node.size()) + " vertices, " +
            std::to_string(in.motion->body().triangles.size()) + " triangles, thickness " +
            fmt("%.4g m", in.motion->body().thickness) + " (rest surface reproduced to " + fmt("%.1e m", in.rest_mismatch) +
            ")");
  log::info(c.motion.string() + ": " + std::to_string(in.frame_time.size()) + " frames, " +
            (in.layout.wrap ? "periodic, spline period " + fmt("%.6g s", *in.layout.wrap)
                            : "not periodic" + (in.layout.note.empty() ? std::string() : " (" + in.layout.note + ")")));
  cfd::io::FinFlowStats st;
  cfd::io::FinCheckpointing ck;
  ck.every = c.checkpoint_every;
  ck.file = !c.checkpoint.empty() ? c.checkpoint
                                  : c.out.parent_path() / (c.out.stem().string() + ".checkpoint.h5");
  ck.restart = c.restart;
  // Progress counts the steps of this run (a restart's ETA from its own rate); the line names the
  // run's step.
  std::unique_ptr<log::Progress> progress;
  long first = 0;
  const auto report = [&](long n, long total, const cfd::StepStats& s) {
    if (!progress) {
      first = n - 1;
      progress = std::make_unique<log::Progress>(
          first ? "fin-cfd fin steps since the restart at step " + std::to_string(first) : std::string("fin-cfd fin step"),
          static_cast<std::size_t>(total - first));
    }
    progress->update(static_cast<std::size_t>(n - first),
                     (first ? "step " + std::to_string(n) + "/" + std::to_string(total) + "  " : std::string()) + "t " +
                         fmt("%.5f s", s.time) + "  CFL " + fmt("%.3f", s.cfl) + "  Poisson " +
                         std::to_string(s.poisson_iterations) + " it  div " + fmt("%.1e", s.max_divergence));
  };
  // Flow-field snapshots (velocity, pressure, vorticity, lambda_2) every snapshot_every-th output
  // time, frame by frame; a restart keeps the frames before its first output and rewrites the rest.
  std::unique_ptr<vtkio::GridSeries> series;
  const fs::path pvd = c.out.parent_path() / (c.out.stem().string() + ".flow.pvd");
  if (c.snapshot_every > 0)
    ck.at_output = [&](long output, double t, const cfd::FlowSolver& solver) {
      if (output % c.snapshot_every != 0) return;
      const auto& g = solver.grid();
      if (!series) {
        series = std::make_unique<vtkio::GridSeries>(pvd, g.axis(0).faces(), g.axis(1).faces(), g.axis(2).faces());
        if (!ck.restart.empty()) series->resume(t - 1e-9 * st.dt);
      }
      vtkio::GridFrame frame;
      const std::size_t n = g.cells();
      for (cfd::StateArray& a : solver.cell_output()) {
        const std::size_t k = a.values.size() / n;
        frame.cell_data.push_back(
            {a.name, NdArray<double>(k == 1 ? std::vector<std::size_t>{n} : std::vector<std::size_t>{n, k},
                                     std::move(a.values))});
      }
      series->add(t, frame);
    };
  if (!ck.restart.empty()) log::info("restarting from " + ck.restart.string());
  stage::Loads loads = cfd::io::run_fin_flow(in, c.flow, st, report, ck);
  if (progress) progress->finish("t " + fmt("%.5f s", st.t_end));
  if (series) log::info("wrote " + std::to_string(series->size()) + " flow snapshots to " + pvd.string());
  if (st.checkpoints > 0)
    log::info("wrote " + std::to_string(st.checkpoints) + " checkpoints to " + ck.file.string() + " (" +
              fmt("%.2f s", st.checkpoint_seconds) + " in all)");
  const auto& g = st.grid;
  log::info("grid " + std::to_string(g.nx()) + " x " + std::to_string(g.ny()) + " x " + std::to_string(g.nz()) + " (h = c/" +
            fmt("%.3g", st.chord / st.h) + ", body thickness " + fmt("%.2f", in.motion->body().thickness / st.h) +
            " h), U " + fmt("%.4g m/s", st.U) + ", nu " + fmt("%.4g m2/s", st.nu) + ", dt " + fmt("%.4g s", st.dt) + ", " +
            std::to_string(st.steps) + " steps, max CFL " + fmt("%.3f", st.max_cfl) + ", mean Poisson iterations " +
            fmt("%.2f", st.steps ? static_cast<double>(st.poisson_iterations) / st.steps : 0.0) + ", " +
            fmt("%.1f s", st.wall_seconds));
  if (in.motion->body().thickness < 2 * st.h)
    log::warn("the closed thin body is " + fmt("%.2f", in.motion->body().thickness / st.h) +
              " cells thick (fewer than 2): raise --cells-per-chord or mesh.h5's ibm_thickness");
  Provenance prov{"fin-cfd", cli::effective_config(app), {c.mesh, c.motion}};
  prov.config["achieved"] = {{"grid", {g.nx(), g.ny(), g.nz()}}, {"h", st.h}, {"dt", st.dt}, {"steps", st.steps},
                             {"U", st.U}, {"nu", st.nu}, {"chord", st.chord}, {"t_begin", st.t_begin},
                             {"t_end", st.t_end}};
  for (std::size_t k = 0; k < loads.time.size(); ++k)
    log::debug("t " + fmt("%.5f s", loads.time(k)) + "  C_T " + fmt("%+.4f", loads.thrust(k)) + "  C_Y " +
               fmt("%+.4f", loads.lateral(k)) + "  C_Z " + fmt("%+.4f", loads.vertical(k)));
  stage::write(c.out, loads, prov);
  log::info("wrote " + c.out.string() + " (" + std::to_string(loads.time.size()) + " output times)");
  if (c.summary.empty()) return kExitOk;

  // Validation: re-read what was written; the nodal loads must sum to the integrated force.
  const auto back = stage::read<stage::Loads>(c.out);
  const auto err = cfd::io::nodal_sum_relative_error(back);
  const double worst = err.empty() ? 0.0 : *std::max_element(err.begin(), err.end());
  const std::size_t nt = back.time.size();
  double ct = 0, cy = 0, cz = 0, ct_max = -1e300, cy_amp = 0;
  for (std::size_t k = 0; k < nt; ++k) {
    ct += back.thrust(k) / nt;
    cy += back.lateral(k) / nt;
    cz += back.vertical(k) / nt;
    ct_max = std::max(ct_max, back.thrust(k));
    cy_amp = std::max(cy_amp, std::abs(back.lateral(k)));
  }
  const std::string name = c.summary.parent_path().filename().string();
  Summary s("validation", name.empty() ? "fin_loads" : name,
            "fin-cfd fin on " + c.mesh.filename().string() + " + " + c.motion.filename().string() +
                ": the nodal loads of loads.h5 sum to the force integrated from the surface traction at every output "
                "time; force coefficients for information");
  s.at_most("max_relative_nodal_sum_error", worst, 0.005, "issue 4: nodal loads sum to the integrated force within 0.5%");
  s.info("CT_mean", ct);
  s.info("CT_max", ct_max);
  s.info("CY_mean", cy);
  s.info("CY_max_abs", cy_amp);
  s.info("CZ_mean", cz);
  s.info("output_times", static_cast<double>(nt));
  s.info("steps", static_cast<double>(st.steps));
  s.info("cells", static_cast<double>(g.cells()));
  s.info("body_thickness_over_h", in.motion->body().thickness / st.h);
  s.info("max_cfl", st.max_cfl);
  s.info("mean_poisson_iterations", st.steps ? static_cast<double>(st.poisson_iterations) / st.steps : 0.0);
  s.info("solver_seconds", st.wall_seconds, "s");
  s.parameters() = prov.config;
  s.set_timing(st.wall_seconds, cli::threads_in_use());
  s.write(c.summary);
  log::info("nodal loads vs integrated force: max relative difference " + fmt("%.3e", worst) + " over " +
            std::to_string(nt) + " output times; C_T mean " + fmt("%.4f", ct) + ", C_Y mean " + fmt("%.4f", cy) +
            "; wrote " + c.summary.string() + (s.pass() ? " (all metrics pass)" : " (a metric FAILED)"));
  return s.pass() ? kExitOk : kExitDifferent;
}

int run_plate(const FinCommands& c, const CLI::App& app, bool coarse) {
  cfd::io::ThinPlateSetup p;
  p.thickness = c.plate_thickness * p.chord;
  p.frames = c.plate_frames;
  if (coarse) {
    p.nx = 6;
    p.nz = 8;
  }
  auto files = cfd::io::make_thin_plate(p);
  Provenance prov{"fin-cfd", cli::effective_config(app), {}};
  prov.config["plate"] = {{"chord", p.chord}, {"span", p.span}, {"nx", p.nx}, {"nz", p.nz}, {"thickness", p.thickness},
                          {"heave", p.heave}, {"pitch", p.pitch}, {"phase", p.phase}, {"pivot", p.pivot},
                          {"period", p.period}, {"frames", p.frames}};
  stage::write(c.plate_mesh, files.mesh, prov);
  stage::write(c.plate_motion, files.motion, prov);
  log::info("thin plate " + fmt("%.3g m", p.chord) + " x " + fmt("%.3g m", p.span) + ", " +
            std::to_string(files.mesh.points.dim(0)) + " nodes, heave " + fmt("%.3g m", p.heave) + ", pitch " +
            fmt("%.3g rad", p.pitch) + ", T " + fmt("%.3g s", p.period) + ": wrote " + c.plate_mesh.string() + ", " +
            c.plate_motion.string());
  return kExitOk;
}

}  // namespace

FinCommands* add_fin_commands(CLI::App& app) {
  static FinCommands c;
  auto& o = c.flow;
  c.fin = app.add_subcommand("fin", "prescribed-motion flow around the fin (mesh.h5 + motion.h5) -> loads.h5");
  auto* f = c.fin;
  f->add_option("--mesh", c.mesh, "mesh.h5 (fin-mesh)")->required()->check(CLI::ExistingFile);
  f->add_option("--motion", c.motion, "motion.h5 (fin-mesh)")->required()->check(CLI::ExistingFile);
  f->add_option("--out", c.out, "output loads.h5")->required();
  f->add_option("--summary", c.summary, "also write a validation summary.json (nodal loads sum check)");
  f->add_option("--reynolds", o.reynolds, "chord Reynolds number U c / nu")->capture_default_str();
  f->add_option("--speed", o.speed, "free-stream speed U [m/s]; 0: U = Re nu / c")->capture_default_str();
  f->add_option("--viscosity", o.viscosity, "kinematic viscosity [m2/s] used when --speed is 0")->capture_default_str();
  f->add_option("--rho", o.rho, "fluid density [kg/m3]")->capture_default_str();
  f->add_option("--chord", o.chord, "chord c [m]; 0: mesh.h5 attribute chord")->capture_default_str();
  f->add_option("--cells-per-chord", o.cells_per_chord, "core cell width h = c / N; 0: min(c/16, ibm_thickness/2)")
      ->capture_default_str();
  f->add_option("--core-margin", o.core_margin, "uniform core beyond the swept box [c]")->capture_default_str();
  f->add_option("--wake", o.wake, "uniform core extension downstream [c]")->capture_default_str();
  f->add_option("--upstream", o.upstream, "domain inlet distance from the swept box [c]")->capture_default_str();
  f->add_option("--downstream", o.downstream, "domain outlet distance from the swept box [c]")->capture_default_str();
  f->add_option("--lateral", o.lateral, "domain half-width beyond the swept box in y [c]")->capture_default_str();
  f->add_option("--spanwise", o.spanwise, "domain extent beyond the swept box in z [c]")->capture_default_str();
  f->add_option("--stretch-ratio", o.stretch_ratio, "largest neighbouring cell-width ratio")->capture_default_str();
  f->add_option("--cfl", o.cfl, "target convective CFL number (sets the fixed time step)")->capture_default_str();
  f->add_option("--cfl-limit", o.cfl_limit, "blow-up guard: stop when the CFL number exceeds this")->capture_default_str();
  f->add_option("--periods", o.periods, "periodic motion: periods simulated")->capture_default_str();
  f->add_option("--output-periods", o.output_periods, "periodic motion: last periods written (0: all)")
      ->capture_default_str();
  f->add_option("--output-interval", o.output_interval, "time between outputs [s]; 0: the motion's frame spacing")
      ->capture_default_str();
  f->add_option("--poisson-rtol", o.poisson_rtol, "pressure Poisson relative tolerance")->capture_default_str();
  f->add_flag("--staircase-balance{false}", o.cut_cells,
              "mass balance: close the faces of every non-fluid cell, moving with the wall (the staircase "
              "balance), instead of the cut-cell one (Seo & Mittal 2011; on the default fin 2.3x less noise in "
              "the lateral force)");
  f->add_option("--checkpoint-every", c.checkpoint_every, "write a checkpoint every N steps (0: never)")
      ->capture_default_str();
  f->add_option("--checkpoint", c.checkpoint, "checkpoint file (default: <out stem>.checkpoint.h5 next to --out)");
  f->add_option("--restart", c.restart, "continue from this checkpoint (same inputs and options)")
      ->check(CLI::ExistingFile);
  f->add_option("--snapshot-every", c.snapshot_every,
                "write the flow field (velocity, pressure, vorticity, lambda2) every N-th output time to "
                "<out stem>.flow.pvd (ParaView; 0: never)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);

  c.plate = app.add_subcommand("thin_plate", "heaving and pitching rigid thin plate as mesh.h5 + motion.h5");
  c.plate->add_option("--mesh", c.plate_mesh, "output mesh.h5")->required();
  c.plate->add_option("--motion", c.plate_motion, "output motion.h5")->required();
  c.plate->add_option("--thickness", c.plate_thickness, "closed-body thickness / chord")->capture_default_str();
  c.plate->add_option("--frames", c.plate_frames, "samples per period")->capture_default_str();
  return &c;
}

bool run_fin_commands(const FinCommands& c, const CLI::App& app, bool coarse, int& exit_code) {
  if (c.fin && *c.fin) {
    exit_code = run_fin(c, app);
    return true;
  }
  if (c.plate && *c.plate) {
    exit_code = run_plate(c, app, coarse);
    return true;
  }
  return false;
}

}  // namespace finverse::fin_cfd
