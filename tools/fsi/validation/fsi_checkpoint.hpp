// Checkpoints of a coupled flow-structure run (issue 32 "Outputs": a restart reproduces the
// uninterrupted run bit for bit). One HDF5 file (cfd/io/flow_checkpoint.hpp's, written to a
// temporary and renamed) holds the flow solver's state and, in its group `run`, everything else the
// future of the run depends on: the coupling's accepted interface motion (x^N, x^{N-1} for the
// predictor, the accepted iteration's input, whose velocity is the flow wall's V^n), the structure's
// generalized-alpha state (positions, rotations, velocities, accelerations, the integrator's
// old-step terms and force scale, the interface load F_I^n), the acceleration's carried history
// (IQN-ILS's reused columns, Aitken's omega), and what the run has recorded so far (per-step
// records and coupling statistics, the probe history, the fsi.h5 frames). The run's options are
// stored as JSON (root attribute `config`); a restart compares them key by key.
#pragma once

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "cfd/flow/flow_solver.hpp"
#include "fem/generalized_alpha.hpp"
#include "fsi/acceleration.hpp"
#include "fsi/implicit_coupling.hpp"
#include "fsi/validation/flow_structure_step.hpp"
#include "fsi/validation/fsi_output.hpp"

namespace finverse::fsi::validation {

// The run's state at the end of an accepted step, besides the flow.
struct FsiRunState {
  Eigen::VectorXd coupling_state, coupling_previous, coupling_input;
  double time = 0;
  long steps = 0;
  fem::DynamicState structure;
  fem::GeneralizedAlpha::Snapshot integrator;
  Eigen::VectorXd interface_load;
  Acceleration::CarriedState acceleration;
  std::vector<StepRecord> records;
  std::vector<StepStatistics> statistics;  // without the residual histories
  std::vector<double> ux_a, uy_a, energy;
  FsiOutput::Arrays frames;
};

// Atomic write (temporary + rename); throws finverse::Error.
void write_fsi_checkpoint(const std::filesystem::path& path, const cfd::FlowSolver& flow, const nlohmann::json& config,
                          const FsiRunState& state);

// Throws finverse::Error in one line naming the file and the first key whose value differs from
// `config` (keys in `may_differ` excepted), or when the file is not a coupled run's checkpoint;
// returns the stored options.
nlohmann::json check_fsi_checkpoint_config(const std::filesystem::path& path, const nlohmann::json& config,
                                 const std::set<std::string>& may_differ);

// The flow is restored into `flow` (set up exactly as the writer's); the rest is returned.
FsiRunState read_fsi_checkpoint(const std::filesystem::path& path, cfd::FlowSolver& flow);

}  // namespace finverse::fsi::validation
