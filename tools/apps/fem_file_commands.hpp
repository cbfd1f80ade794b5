// The stage-file subcommands of fin-fem: `run` (a structural run from mesh, materials, loads and
// root motion; fem/io/file_run.hpp) and `loads` (the quasi-steady loads of an analytic root
// drive; fem/io/quasi_steady_loads.hpp). Flags only: the work is in the fem/io library.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "fem/io/file_run.hpp"
#include "fem/io/quasi_steady_loads.hpp"
#include "fem/sparse_solver.hpp"

namespace finverse::apps {

// `fin-fem run`: a structural run from stage files.
struct FemRunCommand {
  finverse::fem::io::FileRunOptions file_run;
  std::string mesh_path, materials_path, loads_path, motion_path, out_path, pvd_path, effects_path, drive_path;
  std::string analysis = "quasi_static", root_rotation = "fit";
  std::vector<double> gravity{0, 0, 0};
  CLI::App* rn = nullptr;

  void add(CLI::App& app);
  int execute(finverse::fem::SolverBackend backend, const nlohmann::json& config);
};

// `fin-fem loads`: the quasi-steady loads of the root drive's rigid motion.
CLI::App* add_fem_loads_command(CLI::App& app, finverse::fem::io::FileLoadsOptions& qs);

}  // namespace finverse::apps
