// The body of `fin-fit run` (issue 31; DESIGN.md section 5.4): stage files in, materials.h5 out.
// Reads mesh.h5, the target motion (motion.h5: the reconstruction, whose root nodes also drive
// the model), loads.h5, the base materials file (densities, the values of parameters not fitted)
// and the parameter specification (default: membrane E, every ray's E, one nu); builds the fin
// model factory and the objective -- eq. (2) quasi-static increments at the given instants, or
// eq. (1) the dynamic run from rest compared over the target's last period -- and runs the fit
// (fit_driver.hpp) with progress per generation. Every input problem is found before the first
// generation (one evaluation at the materials file's values) and thrown with the file named;
// nothing is written then. Parameters the data cannot constrain are flagged in the file and
// warned about.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "fem/root_motion.hpp"
#include "fit/fin_parameters.hpp"
#include "fit/fit_driver.hpp"
#include "fit/fit_result.hpp"
#include "fit/quasi_static_objective.hpp"

namespace finverse::fit::io {

struct FileFitOptions {
  std::filesystem::path mesh, motion, materials, out;
  std::optional<std::filesystem::path> loads, parameters, summary;
  std::string objective = "quasi_static";  // "dynamic" (eq. (1)) or "static" (load levels)
  // quasi_static: explicit instants [s], else `instant_count` instants spread evenly over the
  // target's span starting at mid-span (1: the paper's mid-swing); dt 0 = the frame spacing.
  std::vector<double> instants;
  int instant_count = 1;
  double dt = 0;
  // dynamic: substeps per frame interval; the compared window is the target's last `periods`
  // of its period (motion.h5 T), or every frame when not periodic.
  int substeps = 4;
  double periods = 1;
  double ramp = 0;  // s of ramp from rest before the first sample (0: ten frame intervals)
  // Root rotations of the drive: fit (root nodes + the rays' tangents at the root) or zero (a
  // clamp that does not turn), fem/root_motion.hpp; unset: zero for a structural load case
  // (nodal_loads.h5) or static load levels, fit otherwise.
  std::optional<fem::RootRotation> root_rotation;
  // quasi_static: the base as the stress-free reference of the increment (QuasiStaticOptions).
  bool stress_free_base = false;
  // quasi_static: eq. (2) with inertia, and how each increment is solved (QuasiStaticOptions).
  bool inertia = false;
  QuasiStaticOptions::Solve increment = QuasiStaticOptions::Solve::newton;
  bool reuse_reference_tangent = true;  // QuasiStaticOptions' (benchmarks only)
  // quasi_static with a converged increment (newton, stored): the GA and CMA-ES explore with the linearised one,
  // the polish and the intervals use Newton's (fit_driver.hpp's explore; goal 8 of issue 45).
  bool explore_linear = false;
  // A synthetic check (issue 45, goal 6): the motion, target and drive alike, with isotropic
  // Gaussian noise of this mean vertex error [fraction of the mesh's chord] (0: none) and seed.
  double target_noise = 0;
  std::uint64_t target_noise_seed = 1;
  FitOptions fit;
};

// The fit as `fin-fit run` sets it up: the parameter space, the fin model factory and the
// objective, with a one-line description of the objective. Reads and checks every input file.
struct FitProblem {
  ParameterSpace space;
  std::shared_ptr<FinModelFactory> factory;
  std::unique_ptr<ResidualFunction> objective;
  std::unique_ptr<ResidualFunction> explore;  // null: the optimisers explore with `objective`
  std::string description;
};
FitProblem load_fit_problem(const FileFitOptions& options);

// `fin-fit evaluate`: the objective at given parameter values (the materials file's where not
// given), in total and per instant / frame / load level. Throws InvalidInput for a name that is
// not a parameter.
struct MisfitReport {
  std::string description;
  std::vector<std::string> names;
  Eigen::VectorXd values;
  double total = 0;  // distance objective J [m]
  std::vector<double> block_times, block_misfit;
};
MisfitReport evaluate_misfit(const FileFitOptions& options, const std::vector<std::pair<std::string, double>>& at);
// The report as fin-fit evaluate prints it: the parameters, the misfit, the misfit per block.
std::string format_misfit(const MisfitReport& report);
// "NAME=VALUE" entries (fin-fit evaluate --at); throws InvalidInput naming a malformed one.
std::vector<std::pair<std::string, double>> parse_parameter_values(const std::vector<std::string>& entries);

// Throws fit::InvalidInput / fem::InvalidInput / finverse::Error naming the file for bad input.
// Under an MPI launcher the ranks share the evaluations (fit/rank_pool.hpp); a serving rank
// writes nothing and returns an empty result.
FitResult run_fit_from_files(const FileFitOptions& options, const nlohmann::json& config);

}  // namespace finverse::fit::io
