// Checkpoints of the flow solver: every array of FlowSolver::state() in one HDF5 file (schema
// finverse/cfd-checkpoint, written atomically through core/hdf5_file.hpp), and the restore that
// makes a restarted run continue bitwise as the uninterrupted one (doubles are stored exactly).
// Lives in finverse_cfd_io so the numerical library itself does not depend on HDF5.
#pragma once

#include <filesystem>
#include <string>

#include "cfd/flow_solver.hpp"

namespace finverse::cfd {

// `config` (JSON text) is stored as the root attribute `config` so a restart can check it.
void write_checkpoint(const std::filesystem::path& path, const FlowSolver& solver, const std::string& config = "{}");
// The solver must have been set up exactly as the one that wrote the file.
void read_checkpoint(const std::filesystem::path& path, FlowSolver& solver);

}  // namespace finverse::cfd
