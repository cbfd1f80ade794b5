// The table of the flow solver's validation cases and the options each takes (cases.hpp): one
// place for a case's name, description, flags and case-file keys, so that the command line and the
// case files (case_file.hpp) cannot drift apart.
#include <algorithm>

#include "cfd/validation/cases.hpp"

namespace finverse::cfd::validation {

const std::vector<ValidationCase>& validation_cases() {
  static const std::vector<ValidationCase> cases = {
      {"taylor_green", "order of accuracy in space and time (2-D Taylor-Green vortex)", run_taylor_green},
      {"channel", "inlet/outlet channel: Poiseuille profile and pressure gradient", run_channel},
      {"ib_couette", "Couette flow between two immersed circles: observed order", run_ib_couette},
      {"cylinder_towed", "towed cylinder against the fixed cylinder in a stream (Re 20)", run_cylinder_towed},
      {"cylinder_oscillating", "in-line oscillating cylinder (KC 5, Re 100): force spikes", run_cylinder_oscillating},
      {"dfg_2d1", "DFG 2D-1 cylinder benchmark (Re 20, steady), immersed boundary", run_dfg_2d1,
       "data/reference/schaefer_turek.json"},
      {"dfg_2d2", "DFG 2D-2 cylinder benchmark (Re 100, periodic), immersed boundary", run_dfg_2d2,
       "data/reference/schaefer_turek.json"},
      {"dfg_2d3", "DFG 2D-3 cylinder benchmark (sine inflow over 8 s), immersed boundary", run_dfg_2d3,
       "data/reference/schaefer_turek.json"},
      {"turek_hron_cfd2", "Turek-Hron CFD2 (Re 100, steady, rigid flag), immersed boundary", run_turek_hron_cfd2,
       "data/reference/turek_hron.json"},
      {"turek_hron_cfd3", "Turek-Hron CFD3 (Re 200, periodic, rigid flag), immersed boundary", run_turek_hron_cfd3,
       "data/reference/turek_hron.json"},
      {"sphere_re100", "sphere at Re 100 (3-D triangulated immersed boundary): drag", run_sphere_re100,
       "data/reference/sphere.json"},
      {"dfg_3d1z", "DFG 3D-1Z cylinder benchmark (Re 20, steady, 3-D), immersed boundary", run_dfg_3d1z,
       "data/reference/schaefer_turek.json"},
      {"heaving_plate_garrick", "thin plate heaving in a stream (Re 1000): mean thrust against Garrick (1936)",
       run_heaving_plate_garrick, "data/reference/garrick_heaving_plate.json"},
      {"spanwise_plate_2d3d", "heaving/pitching plate across a slab (Re 100): 3-D thin body against the 2-D section",
       run_spanwise_plate_2d3d},
      {"pipe_poiseuille",
       "Poiseuille flow in a round pipe, the fluid inside the immersed wall (Re 1283): profile, shear, dp/dz",
       run_pipe_poiseuille},
      {"sheet_towed_plate",
       "flat plate towed through fluid at rest against the fixed plate in a stream (Re 100): "
       "the zero-thickness sheet and the closed body",
       run_sheet_towed_plate},
  };
  return cases;
}

const ValidationCase* find_case(const std::string& name) {
  const auto& cases = validation_cases();
  const auto it = std::find_if(cases.begin(), cases.end(), [&](const ValidationCase& c) { return c.name == name; });
  return it == cases.end() ? nullptr : &*it;
}

namespace {

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

// Grid, time-step and wall options of the 2-D channel benchmarks (DFG, Turek-Hron).
void add_channel_grid_options(std::vector<CaseOption>& v, CaseOptions& o, bool dfg) {
  v.push_back({"--wake-box", &o.wake_box,
               dfg ? "grid: downstream end x of the uniform box [m] (default 0.6)"
                   : "grid: uniform box's length behind the flag's tip [diameters] (default 1)",
               0, 0, true});
  v.push_back(
      {"--stretch-ratio", &o.stretch_ratio, "grid: largest cell-width ratio outside the uniform box", 1.0, 1.5});
  v.push_back({"--wall-stretch-ratio", &o.wall_stretch_ratio,
               "grid: the same between the box and the channel walls (default: --stretch-ratio, but 0.97 on "
               "dfg_2d2's and 0.98 on turek_hron_cfd3's default grids; 1: the box's spacing out to the walls; "
               "below 1, with a core: cells shrinking towards the walls)",
               0.8, 1.5});
  v.push_back({"--core-cells-per-diameter", &o.core_cells_per_diameter,
               "grid: a finer core of h = D / N around the body (boundary layers), joined to the box by "
               "ratio-1.1 growth (0: none)",
               0, 1000});
  v.push_back({"--core-wake", &o.core_wake,
               "grid: the core's length behind the body [diameters] (DFG: behind the cylinder, default 0.75; "
               "Turek-Hron: behind the flag's tip, default 0.5)",
               0, 0, true});
  // The time step's share of an error: halve the CFL number and compare.
  v.push_back({"--cfl", &o.cfl, "time step: target convective CFL number (default 0.5)", 0.01, 1.0});
  v.push_back({"--staircase-balance", &o.staircase_balance,
               "mass balance: close the faces of every non-fluid cell (the staircase balance) instead of the "
               "default cut-cell balance (Seo & Mittal 2011), to compare"});
  v.push_back({"--zero-wall-pressure-gradient", &o.zero_wall_pressure_gradient,
               "pressure on the body: dp/dn = 0 (Mittal et al. 2008) instead of the default wall momentum "
               "balance dp/dn = -nu d(omega)/ds, to compare"});
}

// Grid, duration and reference file of the immersed-body benchmarks.
void add_body_case_options(std::vector<CaseOption>& v, CaseOptions& o, const ValidationCase& c,
                           const std::string& t_unit) {
  v.push_back({"--cells-per-diameter", &o.cells_per_diameter, "grid: h = D / N in the box around the body", 4, 1000});
  v.push_back({"--t-end", &o.t_end, "simulated time [" + t_unit + "]", 0, 0, true});
  v.push_back({"--reference", &o.reference, "reference values (JSON; default " + c.reference + ")"});
}

}  // namespace

std::vector<CaseOption> case_options(const ValidationCase& c, CaseOptions& o) {
  std::vector<CaseOption> v;
  const std::string& n = c.name;
  if (n == "channel") {
    CaseOption every{"--checkpoint-every", &o.checkpoint_every,
                     "write <out>/channel/checkpoint.h5 every N steps (0: never)"};
    every.show_default = true;
    v.push_back(every);
    CaseOption restart{"--restart", &o.restart, "continue from this checkpoint file"};
    restart.existing_file = true;
    v.push_back(restart);
    v.push_back({"--vtk", &o.vtk, "also write <out>/channel/flow.pvd (ParaView)"});
  } else if (n == "cylinder_towed") {
    v.push_back({"--staircase-balance", &o.staircase_balance,
                 "the towed body without the cut-cell mass balance (to measure what it changes)"});
  } else if (starts_with(n, "dfg_2d")) {
    add_body_case_options(v, o, c, "s");
    add_channel_grid_options(v, o, true);
    CaseOption e{"--wall-extrapolation", &o.wall_extrapolation,
                 "surface traction and dp: extrapolation from the probes at d, 2d to the wall (linear), or with a "
                 "third probe at 3d (quadratic), to compare"};
    e.choices = {"linear", "quadratic"};
    e.show_default = true;
    v.push_back(e);
  } else if (starts_with(n, "turek_hron")) {
    add_body_case_options(v, o, c, "s");
    add_channel_grid_options(v, o, false);
    if (n == "turek_hron_cfd3")
      v.push_back({"--kick-velocity", &o.kick_velocity,
                   "start-up: transverse velocity [m/s] a brief push at t = 2 s gives the near wake to start the "
                   "shedding (default 2; 0: none, the instability grows from round-off)",
                   0.0, 10.0});
  } else if (n == "sphere_re100") {
    add_body_case_options(v, o, c, "D/U");
    v.push_back({"--wall-momentum-balance", &o.wall_momentum_balance,
                 "pressure on the body: the wall momentum balance dp/dn = -nu n . curl(omega) instead of the "
                 "default dp/dn = 0, to compare (on bodies of about 28 cells per diameter or more; the default "
                 "D/20 keeps dp/dn = 0; at D/32 CD 1.0748 against 1.0919, control volume 1.0830 against 1.0878)"});
  } else if (n == "dfg_3d1z") {
    add_body_case_options(v, o, c, "s");
    v.push_back({"--wall-momentum-balance", &o.wall_momentum_balance,
                 "pressure on the body: the wall momentum balance dp/dn = -nu n . curl(omega) instead of the "
                 "default dp/dn = 0, to compare (on bodies of about 28 cells per diameter or more; the default "
                 "D/12 keeps dp/dn = 0)"});
    v.push_back({"--span-cells", &o.span_cells, "cells along z (0: mid-span width about h; a multiple of 8)", 0, 4096});
  } else if (n == "pipe_poiseuille") {
    v.push_back({"--cells-per-diameter", &o.cells_per_diameter, "grid: h = D / N (default 22, h about 1 mm)", 4, 1000});
    v.push_back({"--t-end", &o.t_end, "simulated time [s] (default: three times the pipe over its mean speed)", 0, 0,
                 true});
    v.push_back({"--reynolds", &o.reynolds, "Re = rho U D / mu on the centreline speed (default 1283)", 0, 0, true});
  } else if (n == "heaving_plate_garrick") {
    v.push_back({"--reynolds", &o.reynolds, "Re = U c / nu (default 1000)", 0, 0, true});
    v.push_back({"--reduced-frequency", &o.reduced_frequency, "k = pi f c / U (default 2)", 0, 0, true});
    v.push_back({"--amplitudes", &o.amplitudes,
                 "heave amplitudes h0/c, comma-separated (default 0.025,0.0375,0.05; the smallest is graded)"});
    v.push_back({"--thickness", &o.thickness, "plate thickness t/c, rounded ends (default 0.03)", 0.001, 0.5});
    v.push_back({"--cells-per-chord", &o.cells_per_chord, "grid: h = c / N in the box around the plate's path "
                 "(default 100)", 8, 4000});
    v.push_back({"--periods", &o.periods, "heave periods simulated, the first a smooth start (default 6)", 1, 1000});
    v.push_back({"--periods-averaged", &o.periods_averaged, "the last periods averaged (default 3)", 1, 1000});
    v.push_back({"--cfl", &o.cfl, "time step: dt ~ cfl h / U, a whole number of steps per period (default 0.5)",
                 0.01, 1.0});
    v.push_back({"--reference", &o.reference, "reference source (JSON; default " + c.reference + ")"});
  } else if (n == "spanwise_plate_2d3d") {
    v.push_back({"--reynolds", &o.reynolds, "Re = U c / nu (default 100)", 0, 0, true});
    v.push_back({"--cells-per-chord", &o.cells_per_chord, "grid: h = c / N around the plate's path, the plate 2 h "
                 "thick (default 20)", 8, 4000});
    v.push_back({"--span-cells", &o.span_cells, "slab cells along z between the slip walls (default 8)", 1, 4096});
    v.push_back({"--periods", &o.periods, "periods simulated, the last compared (default 2)", 2, 1000});
    v.push_back({"--cfl", &o.cfl, "time step: dt ~ cfl h / U, a whole number of steps per period (default 0.25)",
                 0.01, 1.0});
    v.push_back({"--thickness", &o.thickness, "closed-body thickness t/c (default 2 h)", 0.001, 0.5});
    v.push_back({"--staircase-balance", &o.staircase_balance,
                 "both runs with the staircase mass balance instead of the cut-cell one (to compare)"});
    v.push_back({"--at-rest", &o.at_rest, "the plate held still: the drag alone (to compare)"});
    v.push_back({"--raw-sheet-force", &o.raw_sheet_force,
                 "sheet: the markers' impulses as the force, without the band correction (to compare)"});
  } else if (n == "sheet_towed_plate") {
    v.push_back({"--cells-per-chord", &o.cells_per_chord, "grid: h = c / N (default 32)", 8, 4000});
    v.push_back({"--cfl", &o.cfl, "time step: dt = cfl h / U (default 0.32)", 0.01, 1.0});
    CaseOption k{"--kernel", &o.kernel, "sheet: regularized delta kernel (default smooth3)"};
    k.choices = {"roma3", "peskin4", "smooth3", "smooth4"};
    v.push_back(k);
    v.push_back({"--marker-spacing", &o.marker_spacing, "sheet: marker spacing in cells (default 1)", 0.25, 4.0});
    v.push_back({"--projections", &o.projections, "sheet: forcing and projection passes per step (default 1)", 1, 10});
    v.push_back({"--raw-sheet-force", &o.raw_sheet_force,
                 "sheet: the markers' impulses as the force, without removing the kernel band's inertia (to "
                 "compare)"});
  }
  return v;
}

int run_case(const ValidationCase& c, CaseOptions o) {
  if (o.reference.empty()) o.reference = c.reference;
  return c.run(o);
}

}  // namespace finverse::cfd::validation
