// The coupled run every case uses; see coupled_run.hpp.
#include "fsi/coupled_run.hpp"

#include <chrono>

#include "core/error.hpp"
#include "core/printf_format.hpp"

namespace finverse::fsi {

CoupledRun::CoupledRun(cfd::FlowSolver& flow, fem::CoupledStructure& structure, CoupledStep& step,
                       ImplicitCoupling& coupling, FsiOutput& output, nlohmann::json config, CoupledRunOptions options)
    : flow_(flow),
      structure_(structure),
      step_(step),
      coupling_(coupling),
      output_(output),
      config_(std::move(config)),
      options_(std::move(options)) {
  if (options_.steps < 1) throw Error(options_.name + ": the run is shorter than one time step");
  if (!(options_.dt > 0)) throw Error(options_.name + ": the coupling time step must be > 0");
  if (options_.checkpoint_every < 0) throw Error(options_.name + ": expected checkpoint_every >= 0");
  flow_.warm_start_repeated_steps(options_.warm_start_repeats);
}

long CoupledRun::restart(CoupledCase& c) {
  if (options_.restart.empty()) return 0;
  const std::filesystem::path& file = options_.restart;
  restart_config_ = check_fsi_checkpoint_config(file, config_, options_.may_differ);
  FsiRunState r = read_fsi_checkpoint(file, flow_);
  const InterfaceLayout layout = coupling_.layout();
  if (r.coupling_input.size() != layout.size() || r.coupling_state.size() != layout.size())
    throw Error(options_.name + ": --restart " + file.string() + " holds an interface of " +
                std::to_string(r.coupling_state.size()) + " values, this run has " + std::to_string(layout.size()));
  if (r.steps >= options_.steps)
    throw Error(options_.name + ": --restart " + file.string() + " ends at step " + std::to_string(r.steps) +
                " (t = " + printf_format("%.6g", r.time) + " s): the run must end beyond it");
  step_.resume(r.coupling_input);
  structure_.restart(r.structure, r.integrator, r.interface_load);
  coupling_.restart(r.coupling_state, r.coupling_previous, r.coupling_input, r.time, r.steps);
  // Another acceleration starts without the carried history.
  if (restart_config_.value("acceleration", "") == config_.value("acceleration", ""))
    coupling_.acceleration().restore_carried_state(r.acceleration);
  output_.restore_frames(r.frames);
  statistics_ = std::move(r.statistics);
  c.restore_history(std::move(r.history));
  first_step_ = r.steps;
  last_checkpoint_ = file.string() + " (step " + std::to_string(first_step_) + ")";
  return first_step_;
}

void CoupledRun::write_checkpoint(const CoupledCase& c) const {
  FsiRunState r;
  r.coupling_state = coupling_.state();
  r.coupling_previous = coupling_.previous_state();
  r.coupling_input = coupling_.accepted_input();
  r.time = coupling_.time();
  r.steps = coupling_.steps();
  r.structure = structure_.state();
  r.integrator = structure_.integrator().snapshot();
  r.interface_load = structure_.interface_load();
  r.acceleration = coupling_.acceleration().carried_state();
  r.statistics = statistics_;
  for (StepStatistics& st : r.statistics) st.residual_history.clear();
  r.history = c.history();
  r.frames = output_.saved_frames();
  write_fsi_checkpoint(options_.checkpoint, flow_, config_, r);
}

std::string CoupledRun::failed(const std::string& what) const {
  if (!last_checkpoint_.empty()) return what + "; last good checkpoint " + last_checkpoint_;
  return options_.checkpoint.empty() ? what : what + "; no checkpoint written yet";
}

void CoupledRun::run(CoupledCase& c) {
  const auto loop0 = std::chrono::steady_clock::now();
  const long steps = options_.steps;
  for (long n = first_step_ + 1; n <= steps; ++n) {
    StepStatistics st;
    try {
      st = coupling_.advance(step_, options_.dt);
    } catch (const CouplingDiverged& e) {
      throw CouplingDiverged(failed(e.what()), e.statistics);
    } catch (const CouplingNotConverged& e) {
      throw CouplingNotConverged(failed(e.what()), e.statistics);
    } catch (const std::exception& e) {
      throw Error(
          failed(options_.name + ": step " + std::to_string(n) + " of " + std::to_string(steps) + ": " + e.what()));
    }
    statistics_.push_back(st);
    try {
      c.after_step(n, st);
    } catch (const std::exception& e) {
      throw Error(failed(options_.name + ": step " + std::to_string(n) + ": " + e.what()));
    }
    if (!options_.checkpoint.empty() &&
        (n == steps || (options_.checkpoint_every > 0 && n % options_.checkpoint_every == 0))) {
      write_checkpoint(c);
      last_checkpoint_ = options_.checkpoint.string() + " (step " + std::to_string(n) + ")";
    }
    if (n == steps) c.after_last_step(n);
    if (options_.progress) {
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - loop0).count();
      const double eta = wall / static_cast<double>(n - first_step_) * static_cast<double>(steps - n);
      options_.progress(c.progress_line(n, st) + ", ETA " + printf_format("%.0f", eta) + " s");
    }
  }
  loop_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - loop0).count();
}

}  // namespace finverse::fsi
