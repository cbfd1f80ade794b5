// Natural and periodic cubic splines in time for many channels (see time_spline.hpp). The second
// derivatives M_k at the knots solve, for every interior (periodic: every) knot k,
//   h_{k-1} M_{k-1} + 2 (h_{k-1} + h_k) M_k + h_k M_{k+1} = 6 [(y_{k+1}-y_k)/h_k - (y_k-y_{k-1})/h_{k-1}],
// with M = 0 at both ends of a natural spline and indices wrapping for a periodic one.
#include "cfd/immersed/time_spline.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseLU>

#include "core/error.hpp"

namespace finverse::cfd {

PeriodicLayout periodic_layout(const std::vector<double>& time, std::optional<double> period) {
  PeriodicLayout out;
  out.frames = time.size();
  if (!period) return out;
  const double T = *period;
  if (!(std::isfinite(T) && T > 0)) {
    out.note = "attribute T = " + std::to_string(T) + " is not a positive period";
    return out;
  }
  if (time.size() < 2) return out;
  const double span = time.back() - time.front();
  double hmax = 0;
  for (std::size_t k = 1; k < time.size(); ++k) hmax = std::max(hmax, time[k] - time[k - 1]);
  const double whole = std::round(span / T);
  if (whole >= 1 && std::abs(span - whole * T) <= 1e-9 * T) {
    // The last sample is t_0 + m T: it repeats the first; the spline wraps at it.
    out.wrap = whole * T;
    out.frames = time.size() - 1;
    if (out.frames < 2) {
      out.wrap.reset();
      out.frames = time.size();
      out.note = "two samples one period apart: nothing to interpolate periodically";
    }
    return out;
  }
  const double m = std::ceil(span / T - 1e-9);
  const double gap = m * T - span;
  if (m >= 1 && gap > 0 && gap <= 1.5 * hmax) {
    out.wrap = m * T;
    return out;
  }
  out.note = "the samples span " + std::to_string(span) + " s, not a whole number of periods T = " +
             std::to_string(T) + " s (up to the last sample or one sample spacing short of it)";
  return out;
}

TimeSpline::TimeSpline(std::vector<double> time, const std::vector<double>& values, std::size_t channels,
                       std::optional<double> wrap, const std::string& what)
    : time_(std::move(time)), channels_(channels), wrap_(wrap), what_(what) {
  const std::size_t n = time_.size();
  if (n < 2) throw Error(what_ + ": " + std::to_string(n) + " time samples, expected at least 2");
  if (values.size() != n * channels_)
    throw Error(what_ + ": " + std::to_string(values.size()) + " values for " + std::to_string(n) + " samples of " +
                std::to_string(channels_) + " channels");
  for (std::size_t k = 1; k < n; ++k)
    if (!(time_[k] > time_[k - 1]))
      throw Error(what_ + ": /time is not strictly increasing at sample " + std::to_string(k) + " (" +
                  std::to_string(time_[k - 1]) + " s, then " + std::to_string(time_[k]) + " s)");
  if (wrap_ && !(*wrap_ > time_.back() - time_.front()))
    throw Error(what_ + ": period " + std::to_string(*wrap_) + " s is not longer than the sampled span");
  y_ = values;
  if (wrap_) {
    // Close the loop: knot t_0 + P carries sample 0.
    time_.push_back(time_.front() + *wrap_);
    y_.insert(y_.end(), values.begin(), values.begin() + static_cast<std::ptrdiff_t>(channels_));
  }
  const std::size_t knots = time_.size();
  m_.assign(knots * channels_, 0.0);
  // Unknowns: periodic M_0..M_{n-1} (M_n = M_0); natural M_1..M_{n-2}.
  const std::size_t first = wrap_ ? 0 : 1, last = wrap_ ? n - 1 : n - 2;  // inclusive
  if (!wrap_ && n == 2) return;  // the straight line
  const auto unknowns = static_cast<Eigen::Index>(last - first + 1);
  auto h = [&](std::size_t k) { return time_[k + 1] - time_[k]; };  // k in [0, knots-1)
  std::vector<Eigen::Triplet<double>> trip;
  Eigen::MatrixXd rhs(unknowns, static_cast<Eigen::Index>(channels_));
  for (std::size_t k = first; k <= last; ++k) {
    const auto row = static_cast<Eigen::Index>(k - first);
    // Neighbours (periodic: knot -1 is n-1, knot n is 0; interval lengths wrap too).
    const std::size_t km = k == 0 ? n - 1 : k - 1, kp = k + 1;  // kp may be n (the wrap knot)
    const double h0 = k == 0 ? h(n - 1) : h(k - 1), h1 = h(k);
    auto col = [&](std::size_t j) -> Eigen::Index {
      const std::size_t jj = (wrap_ && j == n) ? 0 : j;
      return static_cast<Eigen::Index>(jj) - static_cast<Eigen::Index>(first);
    };
    trip.emplace_back(row, col(k), 2 * (h0 + h1));
    if (wrap_ || km >= first) trip.emplace_back(row, col(km), h0);
    if (wrap_ || kp <= last) trip.emplace_back(row, col(kp), h1);
    for (std::size_t c = 0; c < channels_; ++c) {
      const double yk = y_[k * channels_ + c], ym = y_[km * channels_ + c], yp = y_[kp * channels_ + c];
      rhs(row, static_cast<Eigen::Index>(c)) = 6 * ((yp - yk) / h1 - (yk - ym) / h0);
    }
  }
  Eigen::SparseMatrix<double> A(unknowns, unknowns);
  A.setFromTriplets(trip.begin(), trip.end());  // duplicates add up (two-sample periodic spline)
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(A);
  if (lu.info() != Eigen::Success) throw Error(what_ + ": spline system is singular (repeated sample times?)");
  const Eigen::MatrixXd M = lu.solve(rhs);
  for (std::size_t k = first; k <= last; ++k)
    for (std::size_t c = 0; c < channels_; ++c)
      m_[k * channels_ + c] = M(static_cast<Eigen::Index>(k - first), static_cast<Eigen::Index>(c));
  if (wrap_)
    for (std::size_t c = 0; c < channels_; ++c) m_[n * channels_ + c] = m_[c];
}

void TimeSpline::evaluate(double t, double* value, double* first, double* second) const {
  if (time_.empty()) throw Error(what_ + ": spline evaluated before it was built");
  double s = t;
  if (wrap_) {
    s = time_.front() + std::fmod(t - time_.front(), *wrap_);
    if (s < time_.front()) s += *wrap_;
  } else {
    const double tol = 1e-9 * (time_.back() - time_.front());
    if (!(t >= time_.front() - tol && t <= time_.back() + tol))
      throw Error(what_ + ": time " + std::to_string(t) + " s lies outside the sampled span [" +
                  std::to_string(time_.front()) + ", " + std::to_string(time_.back()) + "] s of non-periodic data");
    s = std::clamp(t, time_.front(), time_.back());
  }
  // Interval k with t_k <= s <= t_{k+1}.
  auto it = std::upper_bound(time_.begin(), time_.end(), s);
  std::size_t k = it == time_.begin() ? 0 : static_cast<std::size_t>(it - time_.begin()) - 1;
  k = std::min(k, time_.size() - 2);
  const double h = time_[k + 1] - time_[k];
  const double A = (time_[k + 1] - s) / h, B = (s - time_[k]) / h;
  const double* y0 = &y_[k * channels_];
  const double* y1 = &y_[(k + 1) * channels_];
  const double* m0 = &m_[k * channels_];
  const double* m1 = &m_[(k + 1) * channels_];
  const double cA = (A * A * A - A) * h * h / 6, cB = (B * B * B - B) * h * h / 6;
  const double dA = -(3 * A * A - 1) * h / 6, dB = (3 * B * B - 1) * h / 6;
  for (std::size_t c = 0; c < channels_; ++c) {
    if (value) value[c] = A * y0[c] + B * y1[c] + cA * m0[c] + cB * m1[c];
    if (first) first[c] = (y1[c] - y0[c]) / h + dA * m0[c] + dB * m1[c];
    if (second) second[c] = A * m0[c] + B * m1[c];
  }
}

}  // namespace finverse::cfd
