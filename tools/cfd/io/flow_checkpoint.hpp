// Checkpoints of the flow solver: every array of FlowSolver::state() in one HDF5 file (schema
// finverse/cfd-checkpoint, written atomically through core/hdf5_file.hpp), and the restore that
// makes a restarted run continue bitwise as the uninterrupted one (doubles are stored exactly).
// A run may add arrays of its own (loop counters, the output record so far: group `run`), so
// that its outputs too continue bitwise. Lives in finverse_cfd_io so the numerical library itself
// does not depend on HDF5.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "cfd/flow/flow_solver.hpp"

namespace finverse::cfd {

// `config` (JSON text) is stored as the root attribute `config` so a restart can check it.
// `run`: the caller's arrays (empty ones are not stored and read back empty).
void write_checkpoint(const std::filesystem::path& path, const FlowSolver& solver, const std::string& config = "{}",
                      const std::vector<StateArray>& run = {});
// The solver must have been set up exactly as the one that wrote the file. `run`, if given, names
// the caller's arrays to read (a missing one is read as empty).
void read_checkpoint(const std::filesystem::path& path, FlowSolver& solver, std::vector<StateArray>* run = nullptr);
// The root attribute `config` of a checkpoint (throws finverse::Error when it is not one).
std::string checkpoint_config(const std::filesystem::path& path);

}  // namespace finverse::cfd
