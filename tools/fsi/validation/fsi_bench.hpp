// The coupled run's benchmark (issue 32 "Benchmark", results/bench/fsi.json): from the summaries
// of fin-fsi turek_hron runs restarted on the limit cycle of FSI2 and FSI3 (one per acceleration)
// and of the FSI3 flow with the flag held rigid (--hold-flag-rigid), the mean and maximum coupling
// iterations per step of Aitken and IQN-ILS at the runs' relative residual, and the wall time of
// one coupled FSI3 step over one rigid-flag step. Goals: IQN-ILS <= 5 mean iterations on FSI3 and
// <= 4 on FSI2 (published anchors: solids4foam's IQN-ILS 6.7-7.0 mean, 11-15 max, on FSI3 and 4.6
// on FSI2), step cost ratio <= 3. With the fin's pair (issue 50, Deliver 2): the fsi stage's coupled
// step (fin-fsi fin's summary) over a step of the flow alone on the same grid (fin-cfd fin's), goal
// <= 3 (docs/studies/fsi_step_cost.md).
#pragma once

#include <filesystem>

#include "core/summary.hpp"

namespace finverse::fsi::validation {

struct FsiBenchInputs {
  std::filesystem::path fsi3_iqn_ils, fsi3_aitken, fsi2_iqn_ils, fsi2_aitken, fsi3_rigid;  // summary.json
  // Optional, both or neither: fin-fsi fin's summary.json and fin-cfd fin's on the same grid.
  std::filesystem::path fin_coupled, fin_flow;
};

// Throws finverse::Error naming a file that is missing, not a summary or lacks a metric.
Summary fsi_bench(const FsiBenchInputs& inputs);

}  // namespace finverse::fsi::validation
