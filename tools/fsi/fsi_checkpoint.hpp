// Checkpoints of a coupled flow-structure run (issue 32 "Outputs": a restart reproduces the
// uninterrupted run bit for bit). One HDF5 file (cfd/io/flow_checkpoint.hpp's, written to a
// temporary and renamed) holds the flow solver's state and, in its group `run`, everything else the
// future of the run depends on: the coupling's accepted interface motion (x^N, x^{N-1} for the
// predictor, the accepted iteration's input, whose velocity is the flow wall's V^n), the structure's
// generalized-alpha state (positions, rotations, velocities, accelerations, the integrator's
// old-step terms and force scale, the interface load F_I^n), the acceleration's carried history
// (IQN-ILS's reused columns, Aitken's omega), and what the run has recorded so far (the coupling
// statistics of every step, the fsi.h5 frames and probe history, and the case's own per-step
// series, e.g. the flag's drag and point A, the fin's force and ray tips). The run's options are
// stored as JSON (root attribute `config`); a restart compares them key by key.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "cfd/flow/flow_solver.hpp"
#include "fem/generalized_alpha.hpp"
#include "fsi/acceleration.hpp"
#include "fsi/fsi_output.hpp"
#include "fsi/implicit_coupling.hpp"

namespace finverse::fsi {

// A case's per-step series by name (flat arrays; the case knows their layout).
using RunHistory = std::map<std::string, std::vector<double>>;

// The run's state at the end of an accepted step, besides the flow.
struct FsiRunState {
  Eigen::VectorXd coupling_state, coupling_previous, coupling_input;
  double time = 0;
  long steps = 0;
  fem::DynamicState structure;
  fem::GeneralizedAlpha::Snapshot integrator;
  Eigen::VectorXd interface_load;
  Acceleration::CarriedState acceleration;
  std::vector<StepStatistics> statistics;  // without the residual histories
  RunHistory history;
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

}  // namespace finverse::fsi
