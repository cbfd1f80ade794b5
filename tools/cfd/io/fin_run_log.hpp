// What fin-cfd fin tells the user on the log (DESIGN.md section 3, "Progress"): the inputs as read,
// the step progress with its ETA (after a restart counted from the restart, so the rate is this
// run's), and the run's one-paragraph account: grid, scales, steps, CFL, checkpoints, and a warning
// when the closed thin body is under two cells thick.
#pragma once

#include <filesystem>
#include <memory>

#include "cfd/flow/flow_solver.hpp"
#include "cfd/io/fin_flow_case.hpp"
#include "cfd/io/fin_input.hpp"
#include "core/log.hpp"

namespace finverse::cfd::io {

void log_fin_input(const FinInput& in, const std::filesystem::path& mesh, const std::filesystem::path& motion);

class FinProgress {
 public:
  // The progress callback of run_fin_flow: step n of total.
  void operator()(long n, long total, const StepStats& s);
  void finish(double t_end);

 private:
  std::unique_ptr<log::Progress> progress_;
  long first_ = 0;  // steps done before this run (a restart's checkpoint)
};

void log_fin_run(const FinInput& in, const FinFlowStats& st, const std::filesystem::path& checkpoint);

}  // namespace finverse::cfd::io
