// The seed paper's Table 1 beside our Turek-Hron FSI2 / FSI3 result (issue 32, validation 2).
// Every column of the table is a peak convention: A_m/D = (|mean| + amplitude) of the tip's u_y
// over D, so Turek-Hron's 0.83 / 0.36 are their mean + amplitude; St = f D / Ubar with f of u_y;
// C_D = mean drag / (rho Ubar^2 D / 2). Our row comes from the run's summary (Am_over_D_peak,
// St, CD_mean), the others from the reference file's seed_paper_table1.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/summary.hpp"

namespace finverse::fsi::validation {

// Text lines of the table for case FSI2 or FSI3 (empty for FSI1, which the table lacks); the
// "ours" row says "no full period" when the summary holds no graded period.
std::vector<std::string> seed_table1_lines(const nlohmann::json& reference, const std::string& case_name,
                                           const Summary& summary);

}  // namespace finverse::fsi::validation
