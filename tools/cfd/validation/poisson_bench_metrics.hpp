// The pressure Poisson part of the flow solver's benchmark file (results/bench/cfd.json;
// fin-cfd-bench --poisson): fin-poisson-bench's summary (finverse MG-PCG against hypre PFMG /
// BoomerAMG on the same stretched all-Neumann matrix) taken over metric by metric under poisson_
// names, its graded time ratios still graded.
#pragma once

#include <nlohmann/json.hpp>

#include "core/summary.hpp"

namespace finverse::cfd::validation {

// Adds `poisson`'s metrics to `cfd`; returns `poisson`'s parameters.
nlohmann::json add_poisson_bench_metrics(Summary& cfd, Summary& poisson);

}  // namespace finverse::cfd::validation
