// The flags of `fin-fsi fin` that set the coupled run itself (FinFsiOptions: the closed thin
// body, the root's ramp, the coupling's acceleration and tolerances, the structure's time
// integration and damping), registered on its CLI11 subcommand; the app keeps the input files and
// fin-cfd's flow flags (cfd/io/fin_flow_case.hpp).
#pragma once

#include <CLI/CLI.hpp>

#include "fsi/fin_fsi_run.hpp"

namespace finverse::fsi {

void add_fin_fsi_flags(CLI::App& command, FinFsiOptions& o);

}  // namespace finverse::fsi
