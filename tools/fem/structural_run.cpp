// Static, quasi-static and dynamic runs over output times (see structural_run.hpp).
#include "fem/structural_run.hpp"

#include <cmath>
#include <sstream>

#include "fem/errors.hpp"
#include "fem/quasi_static_increment.hpp"

namespace finverse::fem {

Analysis parse_analysis(const std::string& name) {
  if (name == "static") return Analysis::static_equilibrium;
  if (name == "quasi_static") return Analysis::quasi_static;
  if (name == "dynamic") return Analysis::dynamic;
  throw InvalidInput("analysis '" + name + "', expected static, quasi_static or dynamic");
}

const char* to_string(Analysis a) {
  switch (a) {
    case Analysis::static_equilibrium: return "static";
    case Analysis::quasi_static: return "quasi_static";
    case Analysis::dynamic: return "dynamic";
  }
  return "?";
}

namespace {
void check_times(const std::vector<double>& t, double start) {
  if (t.empty()) throw InvalidInput("structural run: no output times");
  for (size_t k = 0; k < t.size(); ++k)
    if (!std::isfinite(t[k]) || (k > 0 && !(t[k] > t[k - 1]))) {
      std::ostringstream os;
      os << "structural run: output time[" << k << "] = " << t[k] << ", expected finite and increasing";
      throw InvalidInput(os.str());
    }
  // The run starts unloaded at rest; the data's first frame is reached through the ramp.
  if (!std::isfinite(start) || !(start < t.front()))
    throw InvalidInput("structural run: start time " + std::to_string(start) +
                       " must precede the first output time " + std::to_string(t.front()) +
                       " (the loads and root motion ramp up from rest in between)");
}

// Static continuation from the reference state at start to equilibrium at t0.
int ramp_to_first(StaticSolver& solver, NodalState& state, double start, double t0, int steps) {
  int iterations = 0;
  double t_prev = start;
  for (int j = 1; j <= steps; ++j) {
    const double t = j == steps ? t0 : start + (t0 - start) * j / steps;
    iterations += solver.solve(state, t_prev, t).total_iterations;
    t_prev = t;
  }
  return iterations;
}
}  // namespace

std::vector<RunFrame> run_structural_analysis(const Model& model, const RunOptions& o,
                                              const std::vector<double>& times,
                                              const std::function<void(int, const RunFrame&)>& on_frame) {
  check_times(times, o.start_time);
  if (o.ramp_steps < 1 || o.substeps < 1)
    throw InvalidInput("structural run: ramp_steps and substeps must be >= 1");
  std::vector<RunFrame> frames;
  frames.reserve(times.size());
  auto emit = [&](RunFrame f) {
    frames.push_back(std::move(f));
    if (on_frame) on_frame(static_cast<int>(frames.size()) - 1, frames.back());
  };

  if (o.analysis != Analysis::dynamic) {
    StaticOptions so = o.static_options;
    so.steps = 1;
    QuasiStaticIncrement increment(model, so);
    StaticSolver& solver = increment.solver();
    NodalState state = model.reference_state();
    const int its = ramp_to_first(solver, state, o.start_time, times[0], o.ramp_steps);
    emit({times[0], state, {}, its});
    for (size_t k = 1; k < times.size(); ++k) {
      RunFrame f{times[k], {}, {}, 0};
      if (o.analysis == Analysis::static_equilibrium) {
        f.state = frames.back().state;
        f.iterations = solver.solve(f.state, times[k - 1], times[k]).total_iterations;
      } else {
        QuasiStaticInfo info;
        f.state = increment.solve(frames.back().state, times[k - 1], times[k], &info);
        f.iterations = info.iterations;
      }
      emit(std::move(f));
    }
    return frames;
  }

  // Dynamic: uniform output spacing, integer number of steps in the ramp.
  const double dt_out = times.size() > 1 ? times[1] - times[0] : times[0] - o.start_time;
  for (size_t k = 1; k < times.size(); ++k)
    if (std::abs((times[k] - times[k - 1]) - dt_out) > 1e-6 * dt_out)
      throw InvalidInput("structural run: dynamic analysis needs equally spaced output times (interval " +
                         std::to_string(k) + " differs)");
  if (!(dt_out > 0)) throw InvalidInput("structural run: dynamic analysis needs a positive output interval");
  DynamicOptions dyn = o.dynamic_options;
  dyn.time_step = dt_out / o.substeps;
  const long ramp_steps = std::lround(std::ceil((times[0] - o.start_time) / dyn.time_step - 1e-9));
  GeneralizedAlpha integrator(model, dyn);
  DynamicState s = integrator.reference_state(times[0] - ramp_steps * dyn.time_step);
  integrator.initialize(s);
  // A step that fails names the frame it was heading for and the sub-steps it ran at.
  auto advance = [&](long steps, size_t frame) {
    int its = 0;
    try {
      for (long j = 0; j < steps; ++j) its += integrator.step(s).iterations;
    } catch (const NotConverged& e) {
      std::ostringstream os;
      os << (frame == 0 ? "in the ramp before frame 0"
                        : "between frames " + std::to_string(frame - 1) + " and " + std::to_string(frame))
         << " at " << o.substeps << " sub-steps per frame: " << e.what();
      throw NotConverged(os.str());
    }
    return its;
  };
  int its = advance(ramp_steps, 0);
  s.time = times[0];  // remove the round-off of the summed steps
  emit({times[0], s.configuration, s.velocity, its});
  for (size_t k = 1; k < times.size(); ++k) {
    its = advance(o.substeps, k);
    s.time = times[k];
    emit({times[k], s.configuration, s.velocity, its});
  }
  return frames;
}

}  // namespace finverse::fem
