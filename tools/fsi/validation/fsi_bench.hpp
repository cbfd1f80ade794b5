// The coupled run's benchmark (issue 32 "Benchmark", results/bench/fsi.json): from the summaries
// of fin-fsi turek_hron runs restarted on the limit cycle of FSI2 and FSI3 (one per acceleration)
// and of the FSI3 flow with the flag held rigid (--hold-flag-rigid), the mean and maximum coupling
// iterations per step of Aitken and IQN-ILS at the runs' relative residual, and the wall time of
// one coupled FSI3 step over one rigid-flag step. Goals: IQN-ILS <= 5 mean iterations on FSI3 and
// <= 4 on FSI2 (published anchors: solids4foam's IQN-ILS 6.7-7.0 mean, 11-15 max, on FSI3 and 4.6
// on FSI2), step cost ratio <= 3.
#pragma once

#include <filesystem>

#include "core/summary.hpp"

namespace finverse::fsi::validation {

struct FsiBenchInputs {
  std::filesystem::path fsi3_iqn_ils, fsi3_aitken, fsi2_iqn_ils, fsi2_aitken, fsi3_rigid;  // summary.json
};

// Throws finverse::Error naming a file that is missing, not a summary or lacks a metric.
Summary fsi_bench(const FsiBenchInputs& inputs);

}  // namespace finverse::fsi::validation
