// fin-fem's stage-file subcommands (fem_file_commands.hpp).
#include "fem_file_commands.hpp"

#include <iostream>

namespace finverse::apps {

namespace fio = finverse::fem::io;

void FemRunCommand::add(CLI::App& app) {
  rn = app.add_subcommand("run", "structural run from stage files (mesh, materials, loads, motion)");
  rn->add_option("--mesh", mesh_path, "mesh.h5 (finverse/mesh)")->required();
  rn->add_option("--materials", materials_path, "materials JSON (tools/fem/io/material_spec.hpp)")->required();
  rn->add_option("--loads", loads_path,
                 "loads.h5 of fin-cfd, or nodal_loads.h5 (times and nodal forces only): forces over time");
  rn->add_option("--motion", motion_path, "motion.h5 (finverse/motion): root-node motion over time");
  rn->add_option("--out", out_path, "response file, finverse/motion schema")->required();
  rn->add_option("--pvd", pvd_path, "ParaView series of the shell surface (default: none)");
  rn->add_option("--root-drive", drive_path,
                 "analytic root drive JSON (fem/io/root_drive_file.hpp, frequency_hz) instead of --motion");
  rn->add_option("--periods", file_run.periods, "--root-drive without loads: periods after the drive's ramp")
      ->capture_default_str();
  rn->add_option("--frames-per-period", file_run.frames_per_period,
                 "--root-drive without loads: output frames per period")
      ->capture_default_str();
  rn->add_option("--effects", effects_path, "candidate effects to add to the model: JSON list (tools/fem/effects)");
  rn->add_option("--analysis", analysis, "static, quasi_static (paper eq. 2) or dynamic")->capture_default_str();
  rn->add_option("--root-rotation", root_rotation,
                 "root rotations: fit (root nodes + the rays' tangents at the root) or zero")
      ->capture_default_str();
  rn->add_option("--ramp", file_run.ramp, "s of ramp from rest before the first frame (0: ten frame intervals)")
      ->capture_default_str();
  rn->add_option("--ramp-steps", file_run.run.ramp_steps, "static load steps through the ramp")->capture_default_str();
  rn->add_option("--substeps", file_run.run.substeps, "dynamic: time steps per frame interval")->capture_default_str();
  rn->add_option("--rho-inf", file_run.run.dynamic_options.spectral_radius, "dynamic: generalized-alpha rho_inf")
      ->capture_default_str();
  rn->add_flag_callback(
      "--full-newton", [this] { file_run.run.dynamic_options = fem::with_full_newton(file_run.run.dynamic_options); },
      "dynamic: each step's Newton starts where the last ended and refactorises every iteration: the thin "
      "fin's run at 8 sub-steps per frame needs it, with --rho-inf 0.5 (docs/studies/fin_dynamic_run.md)");
  rn->add_option("--max-iterations", file_run.run.static_options.max_iterations, "Newton iterations per step")
      ->capture_default_str();
  rn->add_option("--gravity", gravity, "gravity vector [m/s^2]")->expected(3)->capture_default_str();
  rn->add_flag("--unsymmetric-tangent", file_run.run.static_options.unsymmetric_tangent,
               "static/quasi_static: full non-symmetric tangent with UMFPACK LU");
}

int FemRunCommand::execute(finverse::fem::SolverBackend backend, const nlohmann::json& config) {
  file_run.mesh = mesh_path;
  file_run.materials = materials_path;
  file_run.out = out_path;
  if (!loads_path.empty()) file_run.loads = loads_path;
  if (!motion_path.empty()) file_run.motion = motion_path;
  if (!pvd_path.empty()) file_run.pvd = pvd_path;
  if (!effects_path.empty()) file_run.effects = effects_path;
  if (!drive_path.empty()) file_run.root_drive = drive_path;
  file_run.run.analysis = finverse::fem::parse_analysis(analysis);
  file_run.root_rotation = finverse::fem::parse_root_rotation(root_rotation);
  file_run.gravity = {gravity[0], gravity[1], gravity[2]};
  file_run.run.static_options.backend = file_run.run.dynamic_options.backend = backend;
  const auto summary = fio::run_from_files(file_run, config);
  std::cerr << "fin-fem run: " << summary.frames << " frames, " << summary.newton_iterations
            << " Newton iterations, wrote " << out_path << "\n";
  return 0;
}

CLI::App* add_fem_loads_command(CLI::App& app, fio::FileLoadsOptions& qs) {
  CLI::App* ld =
      app.add_subcommand("loads", "quasi-steady loads (resistive + added mass) of the root drive's rigid motion");
  ld->add_option("--mesh", qs.mesh, "mesh.h5 (finverse/mesh)")->required();
  ld->add_option("--root-drive", qs.root_drive, "root drive JSON (fem/io/root_drive_file.hpp)")->required();
  ld->add_option("--out", qs.out, "loads.h5 (finverse/loads, with T)")->required();
  ld->add_option("--start-periods", qs.start_periods, "first time, in drive periods")->capture_default_str();
  ld->add_option("--periods", qs.periods, "periods covered")->capture_default_str();
  ld->add_option("--frames-per-period", qs.frames_per_period, "times per period")->capture_default_str();
  ld->add_option("--reynolds", qs.reynolds, "Re = U c / nu (sets U)")->capture_default_str();
  ld->add_option("--density", qs.load.density, "water density [kg m-3]")->capture_default_str();
  ld->add_option("--drag-coefficient", qs.load.drag_coefficient, "C_D of the plate's normal motion")
      ->capture_default_str();
  ld->add_option("--added-mass-coefficient", qs.load.added_mass_coefficient, "C_a: added mass C_a rho c per area")
      ->capture_default_str();
  ld->add_option("--scale", qs.load.scale, "multiplies the whole load")->capture_default_str();
  return ld;
}

}  // namespace finverse::apps
