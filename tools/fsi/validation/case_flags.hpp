// The command-line flags of fin-fsi's validation cases (Turek-Hron FSI1-3, the pitching plate,
// the Hessenthaler plane flow): each case's options registered on its CLI11 subcommand, so that
// tools/apps/fin-fsi.cpp only parses, runs and writes. The flags that name files stay in the app.
#pragma once

#include <CLI/CLI.hpp>

#include "fsi/validation/hessenthaler_phase1_fsi.hpp"
#include "fsi/validation/hessenthaler_plane_fsi.hpp"
#include "fsi/validation/pitching_plate_fsi.hpp"
#include "fsi/validation/turek_hron_fsi.hpp"

namespace finverse::fsi::validation {

void add_turek_hron_flags(CLI::App& command, TurekHronFsiOptions& o);
void add_pitching_plate_flags(CLI::App& command, PitchingPlateOptions& o);
void add_hessenthaler_plane_flags(CLI::App& command, HessenthalerPlaneOptions& o);
void add_hessenthaler_phase1_flags(CLI::App& command, HessenthalerPhaseIOptions& o);

}  // namespace finverse::fsi::validation
