// FlowSolver::warm_start_repeated_steps: a partitioned coupling repeats a step from its restored
// start with an updated interface, and with the option on the repeat's momentum and pressure
// solves start from the previous repeat's solutions. A deforming flap (bending_flap.hpp) is
// stepped from one saved state to two positions in turn:
//   - the second repeat gives the cold repeat's flow within the solvers' tolerances, in fewer
//     pressure-correction iterations;
//   - a step computed for the first time (after restoring a state the solver did not just step
//     from, or a new step after an accepted one) is bitwise the cold solver's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "bending_flap.hpp"
#include "cfd/flow/flow_solver.hpp"

namespace finverse::cfd {
namespace {

constexpr int kRepeatCells = test::kBendingFlapCells;

// The flap solver after five steps, each computed once.
FlowSolver repeat_flap_solver(bool warm) {
  FlowSolver s = test::bending_flap_solver();
  s.warm_start_repeated_steps(warm);
  for (int n = 0; n < 5; ++n) {
    s.set_body_state(test::bending_flap(s.time() + s.next_dt(), 0));
    s.step();
  }
  return s;
}

StepStats repeat_step_to(FlowSolver& s, double dy) {
  s.set_body_state(test::bending_flap(s.time() + s.next_dt(), dy));
  return s.step();
}

double max_state_difference(const std::vector<StateArray>& a, const std::vector<StateArray>& b) {
  double m = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
    for (std::size_t n = 0; n < a[k].values.size(); ++n) m = std::max(m, std::abs(a[k].values[n] - b[k].values[n]));
  return m;
}

TEST(WarmStartedRepeats, ARepeatedStepMatchesTheColdOneInFewerIterations) {
  FlowSolver cold = repeat_flap_solver(false), warm = repeat_flap_solver(true);
  const std::vector<StateArray> saved = cold.state();
  ASSERT_EQ(max_state_difference(saved, warm.state()), 0.0);  // the first steps are each computed once
  // First pass at one position, then the repeat at a position moved by 2 % of a cell.
  const double first = 0.0, second = 0.02 / kRepeatCells;
  int cold_iterations = 0, warm_iterations = 0;
  for (FlowSolver* s : {&cold, &warm}) {
    s->restore(saved);
    repeat_step_to(*s, first);
    s->restore(saved);
    const StepStats st = repeat_step_to(*s, second);
    (s == &cold ? cold_iterations : warm_iterations) = st.poisson_iterations;
  }
  std::printf("repeat's pressure-correction iterations: cold %d, warm %d; largest state difference %.3g\n",
              cold_iterations, warm_iterations, max_state_difference(cold.state(), warm.state()));
  EXPECT_LT(warm_iterations, cold_iterations);
  // Both solves converge to 1e-7 relative (the defaults) from different guesses.
  const double scale = 0.06 * 2 * std::numbers::pi;  // the flap tip's speed amplitude
  EXPECT_LT(max_state_difference(cold.state(), warm.state()), 1e-5 * scale);
  EXPECT_GT(max_state_difference(cold.state(), warm.state()), 0.0);  // the guesses did differ
}

TEST(WarmStartedRepeats, StepsComputedForTheFirstTimeAreBitwiseTheColdOnes) {
  FlowSolver cold = repeat_flap_solver(false), warm = repeat_flap_solver(true);
  const std::vector<StateArray> saved = cold.state();
  // A new step after an accepted one: no repeat.
  repeat_step_to(cold, 0.0);
  repeat_step_to(warm, 0.0);
  EXPECT_EQ(max_state_difference(cold.state(), warm.state()), 0.0);
  // Restoring an older state (as a restart does) is not a repeat of the step just computed.
  repeat_step_to(cold, 0.0);
  repeat_step_to(warm, 0.0);
  cold.restore(saved);
  warm.restore(saved);
  repeat_step_to(cold, 0.01 / kRepeatCells);
  repeat_step_to(warm, 0.01 / kRepeatCells);
  EXPECT_EQ(max_state_difference(cold.state(), warm.state()), 0.0);
}

}  // namespace
}  // namespace finverse::cfd
