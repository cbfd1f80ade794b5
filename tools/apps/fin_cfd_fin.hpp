// fin-cfd's fin subcommands (issue 4; DESIGN.md sections 1, 4, 5.1), kept apart from the solver's
// validation cases in fin-cfd.cpp:
//
//   fin-cfd fin --mesh mesh.h5 --motion motion.h5 --out loads.h5 [--reynolds 1000] [--periods 2] ...
//       prescribed-motion flow around the fin's closed thin body; loads.h5 per the contract;
//       --summary FILE also writes a validation summary (nodal loads sum = integrated force);
//       --checkpoint-every N [--checkpoint FILE] writes checkpoints, --restart FILE continues from
//       one (same inputs and options) to the same loads.h5 datasets bit for bit
//   fin-cfd thin_plate --mesh mesh.h5 --motion motion.h5 [--coarse]
//       the heaving and pitching rigid thin plate of the thin_plate_loads validation as stage files
#pragma once

#include <CLI/CLI.hpp>

namespace finverse::fin_cfd {

struct FinCommands;

// Adds the subcommands to `app`; the returned object holds their options.
FinCommands* add_fin_commands(CLI::App& app);
// Runs the selected fin subcommand; false (and `exit_code` untouched) when none was selected.
bool run_fin_commands(const FinCommands& c, const CLI::App& app, bool coarse, int& exit_code);

}  // namespace finverse::fin_cfd
