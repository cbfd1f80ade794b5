// Cubic-spline interpolation in time of sampled node positions (motion.h5 /points), with the
// velocity and acceleration of the interpolant, so the immersed body's kinematics are exactly the
// derivatives of its positions (the pressure's Neumann datum dp/dn = -a . n needs a continuous
// acceleration: a C2 spline gives one, piecewise-linear or Hermite interpolation would not).
//
//   - periodic data (period P): the periodic cubic spline through the samples t_0 .. t_{n-1} and
//     t_0 + P (= sample 0);
//   - otherwise the natural cubic spline (zero second derivative at both ends) on [t_0, t_{n-1}];
//     it reproduces motion linear in time exactly; with two samples it is the straight line.
// Every channel (node coordinate) shares the knots, so the spline system is factorised once.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace finverse::cfd {

// How a sampled motion with period attribute T wraps around (see periodic_layout()).
struct PeriodicLayout {
  std::optional<double> wrap;  // period of the spline (a whole number of T); empty: not periodic
  std::size_t frames = 0;      // samples the spline uses (the last one is dropped when it repeats the first)
  std::string note;            // why the data are not treated as periodic, for the log
};

// Periodic when the samples span a whole number m of periods either up to the last sample (which
// then repeats the first and is dropped) or up to one closing interval short of it (the gap is at
// most 1.5 of the largest sample spacing, as fin-synth's t_k = k T / n); otherwise non-periodic
// with a note. No T: non-periodic.
PeriodicLayout periodic_layout(const std::vector<double>& time, std::optional<double> period);

class TimeSpline {
 public:
  TimeSpline() = default;
  // time: n >= 2 strictly increasing knots; values: n rows of `channels` values (row-major);
  // wrap: period of a periodic spline (> t_{n-1} - t_0). Throws finverse::Error naming `what`.
  TimeSpline(std::vector<double> time, const std::vector<double>& values, std::size_t channels,
             std::optional<double> wrap, const std::string& what = "motion");

  // Value, first and second derivative of every channel at t (any pointer may be null). Periodic
  // splines accept any t; otherwise t must lie in [t_0, t_{n-1}] (to 1e-9 of the span).
  void evaluate(double t, double* value, double* first, double* second) const;

  std::size_t channels() const { return channels_; }
  double t_begin() const { return time_.front(); }
  double t_end() const { return time_.back(); }  // of the samples used (periodic: the wrap knot excluded)
  const std::optional<double>& wrap() const { return wrap_; }

 private:
  std::vector<double> time_;    // knots (periodic: t_0 .. t_{n-1}, plus t_0 + P appended)
  std::vector<double> y_, m_;   // values and second derivatives per knot [knots x channels]
  std::size_t channels_ = 0;
  std::optional<double> wrap_;
  std::string what_;
};

}  // namespace finverse::cfd
