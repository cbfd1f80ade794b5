// The cost per cell per time step over grid sizes, graded for flatness (flow_cost_flatness.hpp).
#include "cfd/validation/flow_cost_flatness.hpp"

#include <algorithm>
#include <cstdio>

#include "core/error.hpp"

namespace finverse::cfd::validation {

namespace {

std::string tag(int n) { return std::to_string(n) + "^3"; }

}  // namespace

void run_flow_cost_sizes(Summary& summary, const FlowCostSettings& settings,
                         const std::function<void(const FlowCostResult&)>& report) {
  std::vector<double> cost;
  for (int n : settings.sizes) {
    if (n < 8 || n % 4 != 0) throw finverse::Error("--size " + std::to_string(n) + ": need a multiple of 4, >= 8");
    const FlowCostResult r = run_flow_cost_bench(n, settings.warmup, settings.steps, settings.stretch);
    report(r);
    summary.info("step_time_" + tag(n), r.seconds_per_step, "s");
    summary.info("cost_per_cell_step_" + tag(n), 1e-9 * r.ns_per_cell_step, "s");
    summary.info("poisson_iterations_per_step_" + tag(n), r.mean_poisson_iterations);
    summary.info("helmholtz_iterations_per_step_" + tag(n), r.mean_helmholtz_iterations);
    cost.push_back(r.ns_per_cell_step);
  }
  if (cost.size() >= 2) {
    const auto [lo, hi] = std::minmax_element(cost.begin(), cost.end());
    summary.at_most("cost_per_cell_step_spread", *hi / *lo, settings.flat_goal,
                    "issue 4: cost per cell per time step should stay flat over grid sizes");
  }
}

std::string flow_cost_line(const FlowCostResult& r) {
  char line[320];
  std::snprintf(line, sizeof line,
                "Taylor-Green %s: setup %.2f s, %.3f s per step, %.1f ns per cell per step, Poisson %.1f and "
                "Helmholtz %.1f iterations per step, max div %.1e",
                tag(r.n).c_str(), r.setup_s, r.seconds_per_step, r.ns_per_cell_step, r.mean_poisson_iterations,
                r.mean_helmholtz_iterations, r.max_divergence);
  return line;
}

nlohmann::json flow_cost_parameters(const FlowCostSettings& settings) {
  return {{"sizes", settings.sizes},
          {"warmup_steps", settings.warmup},
          {"timed_steps", settings.steps},
          {"stretch", settings.stretch},
          {"case", "3-D Taylor-Green vortex, Re 1600, periodic [0, 2 pi]^3, CFL 0.5"}};
}

}  // namespace finverse::cfd::validation
