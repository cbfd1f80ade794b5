// The thrust measures of the seed paper's Fig. 16 and section 4.4: the mean thrust coefficient over
// the record (time-weighted, trapezoidal, so uneven output steps count by their length) and its
// peak. The paper: mean C_T 0.042 by the reconstruction against 0.058 by its FSI. Thrust is the
// force along -x (DESIGN.md section 3); loads.h5 and fsi.h5 store C_T with that sign already.
#pragma once

#include <vector>

namespace finverse::report {

struct ForceStatistics {
  double mean = 0, peak = 0, minimum = 0;
};

// time ascending [s], c: the coefficient at those times. Throws finverse::Error for an empty or
// mismatched series; one sample gives that sample.
ForceStatistics force_statistics(const std::vector<double>& time, const std::vector<double>& c);

}  // namespace finverse::report
