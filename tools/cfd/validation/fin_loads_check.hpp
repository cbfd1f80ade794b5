// The fin run's self-check (fin-cfd fin --summary; the thin_plate_loads validation case): the nodal
// loads of loads.h5, read back from the file, must sum to the force integrated from the surface
// traction at every output time (DESIGN.md 5.1: "force coefficients and nodal loads come from the
// same traction"); over the last period of a periodic record, issue 30's smoothness goals
// (load_smoothness.hpp); the force coefficients and the run's statistics are reported beside it.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "cfd/io/fin_flow_case.hpp"
#include "core/stage_files.hpp"
#include "core/summary.hpp"

namespace finverse::cfd::validation {

// `name`: the summary's case name; `inputs`: the mesh and motion file names, for its description.
Summary fin_loads_summary(const std::string& name, const std::string& inputs, const stage::Loads& loads,
                          const io::FinFlowStats& stats, double body_thickness, const nlohmann::json& parameters);

}  // namespace finverse::cfd::validation
