// What a flow case (flow_case.hpp) leaves on disk: <dir>/forces.csv, the force history of every
// body (N and coefficients), and <dir>/summary.json in the validation format (core/summary.hpp)
// with the final coefficients, the control-volume force, the run's statistics and the case's
// parameters, so that a user's run reads like a validation case's.
#pragma once

#include <filesystem>

#include "cfd/cases/flow_case.hpp"
#include "core/summary.hpp"

namespace finverse::cfd::cases {

Summary flow_case_summary(const FlowCaseSpec& spec, const FlowCaseResult& result);

void write_force_history(const std::filesystem::path& csv, const FlowCaseSpec& spec, const FlowCaseResult& result);

}  // namespace finverse::cfd::cases
