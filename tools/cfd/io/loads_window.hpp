// The fin run's loads at an output time: the mean of the per-step loads over the output interval
// centred on it (issue 30), not the one step on the output time. On a body two cells thick most
// steps re-classify some cells, and each re-classification gives the pressure a one-step impulse;
// sampling one step in m aliases those impulses into the outputs, the interval mean keeps each
// impulse's momentum and drops its peak (measured: docs/studies/fin_load_noise.md).
// Output k at step s = k m averages steps s - q .. s + q, a box one interval wide (m odd: q = (m-1)/2,
// weights 1; m even: q = m/2, end steps 1/2). Symmetric, so no phase shift; gain sinc(n/N) at
// harmonic n of N outputs per period (0.9836 at the 10th for N = 100). Where the run ends at an
// output (a motion that is not periodic) the window shrinks symmetrically; m = 1 is the step.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "cfd/immersed/vec3.hpp"

namespace finverse::cfd::io {

class LoadsWindow {
 public:
  // m steps per output interval; nodes / shell triangles of the record; the outputs are at the
  // multiples of m in [first_output_step, last_output_step]; the run's steps are 1 .. last_step.
  // sample: every output is its own step's load (no window; the loads as fin-cfd wrote them
  // before issue 30, kept to measure what the window removes).
  LoadsWindow(long m, std::size_t nodes, std::size_t shell, long first_output_step, long last_output_step,
              long last_step, bool sample = false);

  // Whether step n's loads enter some output's window (so the caller evaluates them).
  bool needs(long n) const;

  struct Output {
    long step = 0;
    std::vector<Vec3> nodal;
    Vec3 total{};
    std::vector<double> jump;
  };
  // Adds step n's loads to every window it belongs to; returns the outputs whose windows it closes
  // (in step order). Steps must come in increasing order.
  std::vector<Output> add(long n, const std::vector<Vec3>& nodal, const Vec3& total, const std::vector<double>& jump);

  long steps_per_output() const { return m_; }
  // Half-width (steps) and weight of step n in the window of the output at step s (0 outside).
  long half_width(long s) const;
  double weight(long s, long n) const;

  // The partial sums of the open windows as one flat array (checkpoints) and its inverse.
  std::vector<double> state() const;
  void restore(const std::vector<double>& state);

 private:
  struct Open {
    long step = 0;
    double weight = 0;
    std::vector<double> nodal, jump;  // sums: 3 per node, 1 per shell triangle
    std::array<double, 3> total{};
  };
  long m_, first_, last_out_, last_step_;
  bool sample_;
  std::size_t nodes_, shell_;
  std::vector<Open> open_;  // in step order
};

}  // namespace finverse::cfd::io
