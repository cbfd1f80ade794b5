// The fin's prescribed-motion flow (DESIGN.md sections 1 and 5.1, seed paper section 2.3): the
// moving closed thin body of mesh.h5 + motion.h5 (fin_input.hpp) immersed in a uniform stream on a
// stretched Cartesian grid, stepped with the fractional-step solver, and its loads recorded as
// loads.h5 (loads_record.hpp) from the per-triangle surface forces (nodal_loads.hpp).
//
// Grid: a uniform core of cell width h around the body's swept bounding box (sampled over the run;
// core_margin chords on every side and `wake` chords more downstream), geometric stretching
// (ratio <= stretch_ratio) out to the domain boundaries `upstream`, `downstream`, `lateral`,
// `spanwise` chords beyond the swept box; cell counts multiples of 8 (three multigrid halvings).
// Boundaries: uniform inlet U at x-, convective outlet at x+, free-slip sides.
// Flow: U and nu from the chord Reynolds number Re = U c / nu (U given, or U = Re nu / c for the
// given nu, core/flow_scales.hpp); the stream starts impulsively (the uniform stream projected
// around the body at t_0).
// Time step: fixed, dt = output_interval / m with the smallest m for which the estimated
// convective CFL number (U + 2 x the body's fastest vertex speed) dt / h stays below `cfl`, so
// every output time is a step; the solver's blow-up guard (cfl_limit, non-finite velocity) ends
// the run with a one-line error naming the step.
// Duration: periodic motion runs `periods` periods T from t_0 and writes the last
// `output_periods` of them (0: everything); non-periodic motion runs over the sampled span.
// Checkpoints (fin_flow_checkpoint.hpp): every N steps the solver state, counters and the loads
// record so far, written atomically; a restart continues bitwise as the uninterrupted run. A
// failure during the steps (blow-up, non-finite force, the body leaving the grid) is a one-line
// error naming the step and the last checkpoint written.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cfd/flow/flow_solver.hpp"
#include "cfd/grid/stretched_grid.hpp"
#include "cfd/io/fin_input.hpp"
#include "core/flow_scales.hpp"
#include "core/stage_files.hpp"

namespace finverse::cfd::io {

struct FinFlowOptions {
  double reynolds = 1000;                       // U c / nu (the seed paper's trout caudal fin)
  double speed = 0;                             // U [m/s]; 0: U = reynolds * viscosity / chord
  double viscosity = kWaterKinematicViscosity;  // nu [m^2/s] when speed = 0
  double rho = 1000;                            // [kg/m^3]
  double cells_per_chord = 0;                   // h = c / this; 0: h = min(c / 16, ibm_thickness / 2)
  double core_margin = 0.25;                    // [c]
  double wake = 1.0;                            // [c]
  double upstream = 3, downstream = 6, lateral = 3, spanwise = 3;  // [c]
  double stretch_ratio = 1.12;
  double cfl = 0.5;
  double cfl_limit = 2.0;
  double periods = 2;          // periodic motion
  double output_periods = 1;   // periodic motion: last periods written; 0: all
  double output_interval = 0;  // [s]; 0: the motion's smallest frame spacing (periodic: shortened to divide T)
  double poisson_rtol = 1e-7;
  // The cut-cell mass balance (FlowOptions::cut_cell_continuity_3d, where the measurements are);
  // false: the staircase one, which blows up on fin-mesh's default fin at step 229.
  bool cut_cells = true;
  // Loads at an output time: the mean over the output interval centred on it (loads_window.hpp,
  // the measured noise it removes: docs/studies/fin_load_noise.md); true: the one step on the
  // output time, as before.
  bool sample_loads = false;
  double chord = 0;  // [m]; 0: mesh.h5 attribute chord, else the rest mesh's x extent
  // How the flow sees the fin: "closed", the closed thin body of mesh.h5 /ibm by the ghost-cell
  // method; "sheet", the mid-surface itself as a zero-thickness immersed surface
  // (sheet_forcing.hpp; docs/studies/thin_surface.md), with its delta kernel and marker spacing
  // [cells].
  std::string surface = "closed";
  std::string kernel = "smooth3";
  double marker_spacing = 1.0;
  // The sheet's load: the markers' impulses less the kernel band's inertia
  // (SheetForcingOptions::band_correction); true: the impulses as they are.
  bool raw_sheet_force = false;
  // The sheet's loads at an output time: the one step on it (default), or the mean over the output
  // interval as for the closed body.
  bool sheet_loads_mean = false;
  // > 0: the periodic motion kept to its first K harmonics before it moves the body (fin_input.hpp;
  // read by the caller of read_fin_input, recorded here for the checkpoint's configuration).
  int motion_harmonics = 0;
};

struct FinFlowStats {
  StretchedGrid grid;
  Vec3 swept_lo{}, swept_hi{};
  double h = 0, dt = 0, U = 0, nu = 0, chord = 0, t_begin = 0, t_end = 0, max_body_speed = 0;
  long steps = 0, poisson_iterations = 0;
  double max_cfl = 0, wall_seconds = 0;
  // Of wall_seconds: the pressure's set-ups and solves.
  double pressure_setup_seconds = 0, pressure_solve_seconds = 0;
  std::size_t triangles = 0;
  long first_step = 0;   // steps already done when this run began (a restart's checkpoint)
  long checkpoints = 0;  // written by this run
  double checkpoint_seconds = 0;
};

struct FinCheckpointing {
  long every = 0;                 // write `file` after every this many steps (0: never)
  std::filesystem::path file;     // the checkpoint (replaced atomically each time)
  std::filesystem::path restart;  // continue from this checkpoint (empty: start at t_0)
  // This process writes the checkpoint; false on the other ranks of an MPI run, which keep the
  // cadence to gather the flow's fields with the writer (FlowSolver::gather_rank_lines).
  bool write = true;
  // Called at the end of every step, after its outputs and checkpoint (observers; fault-injection
  // tests); a finverse::Error it throws ends the run as a failure of that step.
  std::function<void(long step, FlowSolver& solver)> after_step;
  // Called at every output time that is written to loads.h5 (after its loads are recorded), e.g.
  // for flow-field snapshots; `output` counts the output times from t_0 (1, 2, ...). On an MPI run
  // set on every rank or on none (the solver's fields are gathered before each call).
  std::function<void(long output, double t, const FlowSolver& solver)> at_output;
};

// The swept bounding box of the body over [t0, t1] (sampled at `samples` times) and the fastest
// vertex speed.
// The numeric options as fin-cfd fin's flags (and `case: fin` keys), with their help texts.
struct FinFlowFlag {
  const char* flag;
  double* value;
  const char* help;
};
std::vector<FinFlowFlag> fin_flow_flags(FinFlowOptions& o);

// mid_surface: of the mid-surface nodes (the sheet) instead of the closed body.
void swept_box(const FinSurfaceMotion& m, double t0, double t1, int samples, Vec3& lo, Vec3& hi, double& max_speed,
               bool mid_surface = false);

// The grid of the header comment around the swept box [lo, hi].
StretchedGrid fin_flow_grid(const Vec3& lo, const Vec3& hi, double chord, double h, const FinFlowOptions& o);

// Runs the flow; `progress(step, steps_total, stats line)` is called after every step.
stage::Loads run_fin_flow(const FinInput& in, const FinFlowOptions& o, FinFlowStats& stats,
                          const std::function<void(long, long, const StepStats&)>& progress = {},
                          const FinCheckpointing& checkpointing = {});

}  // namespace finverse::cfd::io
