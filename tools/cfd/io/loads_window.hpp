// The fin run's loads at an output time as the mean over the output interval centred on it (issue
// 30), instead of the load of the one step that lands on the output time.
//
// Why: on a body two cells thick every step changes the discrete geometry somewhere (a cell is
// covered or cleared, a ghost cell's intercept moves to another face of the closed thin body, an
// image-point stencil changes its substitutions), and the pressure answers each change with a
// short impulse that spreads over the whole body (docs/studies/fin_load_noise.md). The momentum
// that the flow gives the body over an interval is what the time steps resolve; a single step's
// force is not. Sampling one step in m aliases those impulses into the output band, so the
// quasi-static objective (seed paper eq. (2)), which is driven by the load increments between
// outputs, fits noise. The mean over the interval keeps every impulse's momentum and removes its
// peak.
//
// The window: output k at step s = k m (m steps per output interval) is the weighted mean of the
// per-step loads at steps s - q .. s + q, a box exactly one output interval wide (m odd: q = (m-1)/2,
// all weights 1; m even: q = m/2, the two end steps weighted 1/2, shared with the neighbouring
// output). It is symmetric, so it shifts no phase; its gain at harmonic n of a period of N outputs
// is sin(pi n / N) / (pi n / N): 0.99984 at the fundamental and 0.9836 at the 10th harmonic for
// N = 100 (the filter's whole effect below the 10th harmonic). Where the run cannot reach s + q
// (the last output of a non-periodic motion), the window is shortened symmetrically.
// With m = 1 (an output every step) the window is the step itself.
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
