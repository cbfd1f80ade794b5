// The cost part of the flow solver's benchmark file (results/bench/cfd.json; fin-cfd-bench -n): the
// cost benchmark (flow_cost_bench.hpp) at several grid sizes, each size's step time, cost per cell
// per step and iterations as metrics, and the spread of the cost per cell over the sizes graded for
// flatness (issue 4: a solver whose work is O(cells) keeps it flat).
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cfd/validation/flow_cost_bench.hpp"
#include "core/summary.hpp"

namespace finverse::cfd::validation {

struct FlowCostSettings {
  std::vector<int> sizes{64, 96, 128};  // cells per axis, multiples of 4, >= 8
  int warmup = 2;                       // untimed steps before timing
  int steps = 5;                        // timed steps per size
  double stretch = 0.3;                 // grid non-uniformity s of x = xi + s sin(xi), 0 <= s < 1
  double flat_goal = 1.25;              // graded: largest / smallest cost per cell per step <= this
};

// Runs the sizes in turn (a bad size is a finverse::Error naming --size when its turn comes), adds
// each one's metrics and hands its result to `report` as it comes; grades the spread of two sizes
// or more.
void run_flow_cost_sizes(Summary& summary, const FlowCostSettings& settings,
                         const std::function<void(const FlowCostResult&)>& report);

// A size's line for the log: set-up, step time, cost per cell per step, iterations, divergence.
std::string flow_cost_line(const FlowCostResult& r);

// The summary's parameters of the cost part: sizes, steps, stretch and the case.
nlohmann::json flow_cost_parameters(const FlowCostSettings& settings);

}  // namespace finverse::cfd::validation
