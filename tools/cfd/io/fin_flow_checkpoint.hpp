// Checkpoints of fin-cfd's fin run (issue 4: "checkpoints every N steps, and a restart from one
// reproduces the uninterrupted run exactly"; DESIGN.md section 5.1): the flow solver's state
// (flow_checkpoint.hpp; with the moving surface it includes the body's solid-cell velocities, and the
// geometry is re-placed at the checkpoint's time), the run's loop counters and the loads record
// so far, so that a restarted run writes the same loads.h5 datasets bit for bit.
//
// The run's configuration is stored with it: every option that changes the results, keyed by its
// fin-cfd flag, and a SHA-256 fingerprint of the inputs (mesh and motion as read). A restart with a
// different configuration is refused with a one-line error naming the first difference.
// --cfl-limit is left out on purpose: it changes no result, only where a run is stopped, so a run
// stopped by it may be continued with a larger limit.
#pragma once

#include <filesystem>
#include <functional>

#include <nlohmann/json.hpp>

#include "cfd/flow/flow_solver.hpp"
#include "cfd/io/fin_flow_case.hpp"
#include "cfd/io/fin_input.hpp"
#include "cfd/io/loads_record.hpp"
#include "cfd/io/loads_window.hpp"

namespace finverse::cfd::io {

// SHA-256 (hex) of what the flow depends on in the inputs: the rest mid-surface and its shell
// triangles, the closed thin body's definition, the frame times, periodic layout, period and chord,
// and the mid-surface node positions at every frame.
std::string fin_input_fingerprint(const FinInput& in);

// {"options": {flag: value, ...}, "input": fingerprint}.
nlohmann::json fin_flow_config(const FinFlowOptions& o, const FinInput& in);

// Reads the configuration stored in the checkpoint `file` and throws finverse::Error
// "<file>: cannot restart: it was written with --reynolds 100.0, this run has --reynolds 200.0" on
// the first difference from this run's `config` (or when the file is not a fin run's checkpoint).
void check_fin_restart(const std::filesystem::path& file, const nlohmann::json& config);

// The fin run's own counters at a checkpoint.
struct FinRunCounters {
  long step = 0;                // steps done
  long poisson_iterations = 0;  // summed over them
  double max_cfl = 0;
};

void write_fin_checkpoint(const std::filesystem::path& path, const FlowSolver& solver, const nlohmann::json& config,
                          const FinRunCounters& counters, const LoadsRecord& record, const LoadsWindow& window);
// Checks the configuration, then restores the solver (set up and initialised as the writer's),
// the record and the open windows of the loads (loads_window.hpp); returns the counters.
FinRunCounters read_fin_checkpoint(const std::filesystem::path& path, FlowSolver& solver, const nlohmann::json& config,
                                   LoadsRecord& record, LoadsWindow& window);

}  // namespace finverse::cfd::io
