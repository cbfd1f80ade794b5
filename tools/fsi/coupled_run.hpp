// One coupled flow-structure run for every case (issue 44, deliverable 5): the fin, the pitching
// plate, the Turek-Hron flag. A case sets up the flow solver, the structure, the coupled step
// (CoupledStep: FlowStructureStep in 2-D, SurfaceFlowStructureStep in 3-D) and the coupling, and
// then the run is a sequence of named steps, as deal.II's tutorials are:
//   restart()  continue from a checkpoint (fsi_checkpoint.hpp): the flow, the structure, the
//              coupling and its acceleration's history, the fsi.h5 frames and the case's series;
//   run()      every remaining step: the coupling's step, then the case's record of it, then a
//              checkpoint when due, a progress line (step, time, iterations, residual, ETA);
//              a failure names the step and the last good checkpoint;
// and the case grades and writes its outputs (FsiOutput's fsi.h5, FsiParaView's series). A restart
// with the writer's options continues the run bit for bit.
#pragma once

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "cfd/flow/flow_solver.hpp"
#include "fem/coupled_structure.hpp"
#include "fsi/fsi_checkpoint.hpp"
#include "fsi/fsi_output.hpp"
#include "fsi/implicit_coupling.hpp"

namespace finverse::fsi {

struct CoupledRunOptions {
  std::string name = "fsi";  // prefix of failures
  long steps = 0;            // the run ends after this step (counted from the start, restarts included)
  double dt = 0;             // the coupling step [s]
  // Checkpoints: to `checkpoint` (replaced atomically) every checkpoint_every steps (0: only after
  // the last step) and after the last step; none when empty.
  std::filesystem::path checkpoint;
  long checkpoint_every = 0;
  // Continue from this checkpoint; its options must equal this run's config but for `may_differ`.
  // keep_acceleration: restore the acceleration's carried history (only for the same acceleration).
  std::filesystem::path restart;
  std::set<std::string> may_differ;
  std::function<void(const std::string&)> progress;
  // Each coupling iteration after a step's first starts the flow's momentum and pressure solves
  // from the previous iteration's solutions (cfd::FlowSolver::warm_start_repeated_steps); false:
  // from the step's start, as every iteration did before (docs/studies/fsi_step_cost.md).
  bool warm_start_repeats = true;
};

// What a case adds to the run.
class CoupledCase {
 public:
  virtual ~CoupledCase() = default;
  // After every accepted step n (the participants hold its end state): the case's records, fsi.h5
  // frames and flow snapshots.
  virtual void after_step(long n, const StepStatistics& statistics) = 0;
  // After the last step's checkpoint: what the uninterrupted run's checkpoint must not hold (a
  // final frame off the output interval).
  virtual void after_last_step(long /*n*/) {}
  // The case's per-step series, for the checkpoint, and back on a restart.
  [[nodiscard]] virtual RunHistory history() const = 0;
  virtual void restore_history(RunHistory history) = 0;
  // The progress line of step n (after after_step).
  [[nodiscard]] virtual std::string progress_line(long n, const StepStatistics& statistics) const = 0;
};

class CoupledRun {
 public:
  // The participants as the case set them up (flow initialised, structure saved, the coupled step
  // on them); `output` holds the fsi.h5 frames; `config`: the run's options as stored in fsi.h5
  // and checkpoints. All must outlive the run.
  CoupledRun(cfd::FlowSolver& flow, fem::CoupledStructure& structure, CoupledStep& step, ImplicitCoupling& coupling,
             FsiOutput& output, nlohmann::json config, CoupledRunOptions options);

  // From options.restart (nothing without one): the state of the checkpoint's step; returns it.
  // Throws finverse::Error when the file's options differ, its interface does not fit, or it ends at
  // or after options.steps.
  long restart(CoupledCase& c);
  // Steps first_step() + 1 .. options.steps.
  void run(CoupledCase& c);

  [[nodiscard]] long first_step() const { return first_step_; }
  [[nodiscard]] const std::vector<StepStatistics>& statistics() const { return statistics_; }
  [[nodiscard]] double loop_seconds() const { return loop_seconds_; }
  [[nodiscard]] const nlohmann::json& config() const { return config_; }
  // The stored options of the checkpoint restarted from (null without a restart).
  [[nodiscard]] const nlohmann::json& restart_config() const { return restart_config_; }

 private:
  void write_checkpoint(const CoupledCase& c) const;
  [[nodiscard]] std::string failed(const std::string& what) const;

  cfd::FlowSolver& flow_;
  fem::CoupledStructure& structure_;
  CoupledStep& step_;
  ImplicitCoupling& coupling_;
  FsiOutput& output_;
  nlohmann::json config_, restart_config_;
  CoupledRunOptions options_;
  std::vector<StepStatistics> statistics_;
  long first_step_ = 0;
  double loop_seconds_ = 0;
  std::string last_checkpoint_;  // the last good checkpoint, named in a failure
};

}  // namespace finverse::fsi
