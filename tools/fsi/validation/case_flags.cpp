// fin-fsi's validation-case flags (case_flags.hpp).
#include "fsi/validation/case_flags.hpp"

namespace finverse::fsi::validation {

void add_turek_hron_flags(CLI::App& command, TurekHronFsiOptions& o) {
  command.add_option("--case", o.case_name, "FSI1, FSI2 or FSI3")->capture_default_str();
  command.add_option("--acceleration", o.acceleration, "aitken, iqn-ils or constant")->capture_default_str();
  command.add_option("--omega", o.omega, "omega0 (aitken, iqn-ils) or omega (constant)")->capture_default_str();
  command.add_option("--tolerance", o.tolerance, "relative interface displacement residual")->capture_default_str();
  command.add_option("--absolute-tolerance", o.absolute_tolerance, "... or interface displacement change [m]")
      ->capture_default_str();
  command.add_option("--max-iterations", o.max_iterations, "coupling iterations per step")->capture_default_str();
  command.add_option("--cells-per-diameter", o.cells_per_diameter, "flow grid: D / h in the box")
      ->capture_default_str();
  command.add_option("--core-cells-per-diameter", o.core_cells_per_diameter, "finer core around the body: D / h_core")
      ->capture_default_str();
  command.add_option("--core-wake", o.core_wake, "the core ends this many D behind the tip")->capture_default_str();
  command.add_option("--wake-box", o.wake_box, "uniform box behind the tip [D]")->capture_default_str();
  command.add_option("--stretch-ratio", o.stretch_ratio, "largest neighbouring cell-width ratio outside the box")
      ->capture_default_str();
  command
      .add_option("--wall-stretch-ratio", o.wall_stretch_ratio,
                  "the same towards the channel walls; 0: --stretch-ratio")
      ->capture_default_str();
  command.add_option("--channel-length", o.channel_length, "channel length [m] (< 2.5: tests only)")
      ->capture_default_str();
  command.add_option("--ramp-time", o.ramp_time, "inflow ramp time [s]")->capture_default_str();
  command.add_option("--circle-vertices", o.circle_vertices, "cylinder polygon resolution")->capture_default_str();
  command
      .add_option("--surface", o.surface,
                  "closed: the flag in the ghost-cell body; sheet: its wet surface as a zero-thickness sheet")
      ->check(CLI::IsMember({"closed", "sheet"}))
      ->capture_default_str();
  command.add_flag("--band-correction", o.band_correction,
                   "sheet: take the kernel band's inertia off the loads (unstable for light flags)");
  command.add_flag("--subtract-enclosed-fluid", o.subtract_enclosed_fluid,
                   "sheet: the flag's density less the fluid's, which the sheet carries inside the flag");
  command.add_option("--nx", o.mesh.nx, "Q9 elements along the flag")->capture_default_str();
  command.add_option("--ny", o.mesh.ny, "Q9 elements across the flag")->capture_default_str();
  command.add_option("--dt", o.dt, "time step [s]; 0: cfl h / U_max")->capture_default_str();
  command.add_option("--cfl", o.cfl, "CFL number for the default dt")->capture_default_str();
  command.add_option("--t-end", o.t_end, "simulated time [s]; 0: the case's default")->capture_default_str();
  command.add_option("--spectral-radius", o.spectral_radius, "structure's generalized-alpha rho_inf")
      ->capture_default_str();
  command.add_option("--substeps", o.structure_substeps, "structure sub-steps per step")->capture_default_str();
  command.add_option("--output-every", o.output_every, "fsi.h5 frame every k steps")->capture_default_str();
  command
      .add_option("--divergence-iterations", o.divergence_iterations,
                  "residual growing this many iterations in a row: diverged (0: off)")
      ->capture_default_str();
  command.add_option("--checkpoint", o.checkpoint, "checkpoint file (replaced atomically) for --restart");
  command.add_option("--checkpoint-every", o.checkpoint_every, "checkpoint every N steps (0: after the last only)")
      ->capture_default_str();
  command.add_option("--restart", o.restart, "continue from this checkpoint (same options; t_end may grow)")
      ->check(CLI::ExistingFile);
  command.add_flag("--restart-new-coupling", o.restart_new_coupling,
                   "the restart may change acceleration, omega, tolerances and caps (drops the carried history)");
  command.add_option("--paraview", o.paraview_dir, "ParaView series (structure.pvd, flow.pvd) into this directory");
  command.add_option("--paraview-every", o.paraview_every, "ParaView frame every k-th fsi.h5 frame")
      ->capture_default_str();
  command.add_flag("--hold-flag-rigid", o.hold_flag_rigid,
                   "benchmark: from --restart on, the flow alone with the flag frozen (wall time per step)");
  command.add_flag("--cold-repeats", o.cold_repeats,
                   "every coupling iteration's flow solves start from the step's start, not the last iteration's");
}

void add_pitching_plate_flags(CLI::App& command, PitchingPlateOptions& o) {
  command.add_option("--K", o.stiffness, "bending stiffnesses D / (rho_f U^2 L^3), comma-separated")
      ->delimiter(',')
      ->capture_default_str();
  command.add_flag("--rigid", o.rigid, "also run the rigid plate (prescribed pitching)");
  command.add_option("--re", o.re, "Reynolds number U L / nu")->capture_default_str();
  command.add_option("--mass-ratio", o.mass_ratio, "rho_s h / (rho_f L)")->capture_default_str();
  command.add_option("--nx", o.nx, "shell cells along the chord")->capture_default_str();
  command.add_option("--nz", o.nz, "shell cells along the span (even)")->capture_default_str();
  command.add_option("--cells-per-chord", o.cells_per_chord, "flow grid: L / h around the plate")
      ->capture_default_str();
  command.add_option("--thickness-cells", o.thickness_cells, "closed thin body thickness [h]")->capture_default_str();
  command
      .add_option("--surface", o.surface,
                  "how the flow sees the plate: closed (closed thin body) or sheet (zero-thickness mid-surface)")
      ->capture_default_str()
      ->check(CLI::IsMember({"closed", "sheet"}));
  command.add_flag("--band-correction", o.band_correction,
                   "sheet: the plate's load less the kernel band's inertia (see fin-fsi fin --help)");
  command.add_option("--stretch-ratio", o.stretch_ratio, "cell-width ratio outside the uniform box")
      ->capture_default_str();
  command.add_option("--downstream", o.downstream, "domain length behind the trailing edge [L]")->capture_default_str();
  command.add_option("--half-height", o.half_height, "domain half height (y) [L]")->capture_default_str();
  command.add_option("--half-width", o.half_width, "domain half width (z) [L]")->capture_default_str();
  command.add_option("--steps-per-period", o.steps_per_period, "time steps per pitching period")->capture_default_str();
  command.add_option("--periods", o.periods, "periods to run (the last one is measured)")->capture_default_str();
  command.add_option("--ramp-periods", o.ramp_periods, "periods of the smooth start")->capture_default_str();
  command.add_option("--acceleration", o.acceleration, "aitken, iqn-ils or constant")->capture_default_str();
  command.add_option("--omega", o.omega, "omega0 (aitken, iqn-ils) or omega (constant)")->capture_default_str();
  command.add_option("--tolerance", o.tolerance, "relative interface displacement residual")->capture_default_str();
  command.add_option("--absolute-tolerance", o.absolute_tolerance, "... or interface displacement change [L]")
      ->capture_default_str();
  command.add_option("--max-iterations", o.max_iterations, "coupling iterations per step (then the best iterate)")
      ->capture_default_str();
  command.add_option("--structure-tolerance", o.structure_tolerance, "shell Newton residual tolerance")
      ->capture_default_str();
}

void add_hessenthaler_plane_flags(CLI::App& command, HessenthalerPlaneOptions& o) {
  command.add_option("--reference", o.reference, "hessenthaler2017.json")->required();
  command.add_option("--youngs-modulus", o.youngs_modulus, "the flap's E [Pa] (fin-fit flap)")->required();
  command.add_option("--h", o.h, "cell width around the flap [m]")->capture_default_str();
  command.add_option("--t-end", o.t_end, "simulated time [s]")->capture_default_str();
  command.add_option("--ramp-time", o.ramp_time, "inflow ramp [s]")->capture_default_str();
  command.add_option("--cfl", o.cfl, "CFL number of the time step")->capture_default_str();
  command.add_option("--outlet-length", o.outlet_length, "channel length [m]")->capture_default_str();
  command.add_option("--flag-nx", o.mesh.nx, "Q9 elements along the flap")->capture_default_str();
}

void add_hessenthaler_phase1_flags(CLI::App& command, HessenthalerPhaseIOptions& o) {
  command.add_option("--flow", o.flow_case, "fin-cfd case file of the junction (walls, inflows)")
      ->required()
      ->check(CLI::ExistingFile);
  command.add_option("--reference", o.reference, "hessenthaler2017.json")->required()->check(CLI::ExistingFile);
  command.add_option("--centreline", o.centreline, "the MRI centreline (phaseI_centreline.csv)")
      ->required()
      ->check(CLI::ExistingFile);
  command.add_option("--youngs-modulus", o.youngs_modulus, "the flap's E [Pa] (fin-fit flap)")->required();
  command.add_option("--h", o.h, "cell width [m] (default: the case file's grid.h)");
  command.add_option("--flap-along", o.mesh.along, "shell cells along the flap")->capture_default_str();
  command.add_option("--flap-across", o.mesh.across, "shell cells across the flap")->capture_default_str();
  command.add_option("--develop-time", o.develop_time, "the flow's start with the flap held [s]")
      ->capture_default_str();
  command.add_option("--settle-time", o.settle_time, "the flow's settling before each window [s]")
      ->capture_default_str();
  command.add_option("--window-time", o.window_time, "the load's averaging window [s]")->capture_default_str();
  command.add_option("--move-time", o.move_time, "the sheet's step between iterates, at least [s]")
      ->capture_default_str();
  command.add_option("--move-speed", o.move_speed, "the sheet's mean speed between iterates, at most [m/s]")
      ->capture_default_str();
  command.add_option("--omega", o.omega, "the first step's fraction of the way to the answer")->capture_default_str();
  command.add_option("--max-iterations", o.max_iterations, "evaluations of the held flap")->capture_default_str();
  command.add_option("--tolerance", o.tolerance, "converged: the answer's tip within this of the held tip [m]")
      ->capture_default_str();
  command.add_flag("--start-straight", o.start_straight, "start straight instead of the no-flow buoyancy shape");
  command.add_option("--planes", o.planes_file,
                     "write the flow at the end on the planes z = 10 and 30 mm above the clamp (flow_planes.h5)");
  command.add_option("--loads", o.loads_file,
                     "write every evaluation's held tip and mean nodal load (flap_loads.h5, for fin-loop flap --phase1)");
  command.add_option("--viscosity-factor", o.viscosity_factor, "the case's viscosity times this (a flow-side error)")
      ->capture_default_str();
  command.add_option("--inflow-factor", o.inflow_factor, "every inflow's speed times this (a flow-side error)")
      ->capture_default_str();
}

}  // namespace finverse::fsi::validation
