// Smooth and high-frequency parts of a periodic loads history (see load_smoothness.hpp).
#include "cfd/validation/load_smoothness.hpp"

#include <cmath>
#include <complex>
#include <numbers>

namespace finverse::cfd::validation {
namespace {

// X_k = sum_t x_t e^{-2 pi i k t / N}, k = 0 .. N/2 (a real series; a direct sum, N ~ 100).
std::vector<std::complex<double>> half_spectrum(const std::vector<double>& x) {
  const std::size_t n = x.size();
  std::vector<std::complex<double>> X(n / 2 + 1);
  for (std::size_t k = 0; k < X.size(); ++k) {
    std::complex<double> s = 0;
    for (std::size_t t = 0; t < n; ++t)
      s += x[t] * std::polar(1.0, -2 * std::numbers::pi * static_cast<double>((k * t) % n) / static_cast<double>(n));
    X[k] = s;
  }
  return X;
}

struct Sums {
  double high = 0, smooth = 0, raw_increment = 0, smooth_increment = 0;
  void add(const std::vector<double>& x, int K) {
    const std::vector<double> s = smooth_part(x, K);
    for (std::size_t t = 0; t < x.size(); ++t) {
      high += (x[t] - s[t]) * (x[t] - s[t]);
      smooth += s[t] * s[t];
      if (t + 1 < x.size()) {
        raw_increment += (x[t + 1] - x[t]) * (x[t + 1] - x[t]);
        smooth_increment += (s[t + 1] - s[t]) * (s[t + 1] - s[t]);
      }
    }
  }
  double rms_ratio() const { return smooth > 0 ? std::sqrt(high / smooth) : 0.0; }
  double increment_ratio() const { return smooth_increment > 0 ? std::sqrt(raw_increment / smooth_increment) : 0.0; }
};

}  // namespace

std::vector<double> smooth_part(const std::vector<double>& x, int K) {
  const std::size_t n = x.size();
  const auto X = half_spectrum(x);
  std::vector<double> s(n, 0.0);
  for (std::size_t k = 0; k < X.size() && k <= static_cast<std::size_t>(K); ++k) {
    // Each harmonic below Nyquist stands for the pair +-k.
    const double w = (k == 0 || 2 * k == n) ? 1.0 : 2.0;
    for (std::size_t t = 0; t < n; ++t)
      s[t] += w / static_cast<double>(n) *
              (X[k] * std::polar(1.0, 2 * std::numbers::pi * static_cast<double>((k * t) % n) / static_cast<double>(n)))
                  .real();
  }
  return s;
}

double high_frequency_energy_fraction(const std::vector<double>& x, int K) {
  const auto X = half_spectrum(x);
  double high = 0, total = 0;
  for (std::size_t k = 1; k < X.size(); ++k) {
    const double e = std::norm(X[k]) * ((2 * k == x.size()) ? 1.0 : 2.0);
    total += e;
    if (k > static_cast<std::size_t>(K)) high += e;
  }
  return total > 0 ? high / total : 0.0;
}

std::optional<LoadSmoothness> load_smoothness(const stage::Loads& l, int K) {
  const std::size_t nt = l.time.size();
  if (!l.period || nt < 3) return std::nullopt;
  const double dt = l.time(nt - 1) - l.time(nt - 2);
  if (!(dt > 0)) return std::nullopt;
  const long per = std::lround(*l.period / dt);
  if (per < 2 * K + 2 || static_cast<std::size_t>(per) > nt || std::abs(static_cast<double>(per) * dt - *l.period) > 1e-6 * *l.period)
    return std::nullopt;
  const std::size_t n = static_cast<std::size_t>(per), first = nt - n;
  for (std::size_t k = first + 1; k < nt; ++k)
    if (std::abs(l.time(k) - l.time(k - 1) - dt) > 1e-6 * dt) return std::nullopt;
  LoadSmoothness r;
  r.outputs = static_cast<int>(n);
  r.harmonics = K;
  std::vector<double> x(n);
  const auto series = [&](auto&& at) {
    for (std::size_t t = 0; t < n; ++t) x[t] = at(first + t);
    return x;
  };
  r.thrust_energy_fraction = high_frequency_energy_fraction(series([&](std::size_t t) { return l.thrust(t); }), K);
  r.lateral_energy_fraction = high_frequency_energy_fraction(series([&](std::size_t t) { return l.lateral(t); }), K);
  Sums thrust;
  thrust.add(series([&](std::size_t t) { return l.thrust(t); }), K);
  r.thrust_increment_ratio = thrust.increment_ratio();
  Sums nodal, jump;
  for (std::size_t i = 0; i < l.nodal_force.dim(1); ++i)
    for (std::size_t d = 0; d < 3; ++d) nodal.add(series([&](std::size_t t) { return l.nodal_force(t, i, d); }), K);
  for (std::size_t j = 0; j < l.pressure_jump.dim(1); ++j)
    jump.add(series([&](std::size_t t) { return l.pressure_jump(t, j); }), K);
  r.nodal_rms_ratio = nodal.rms_ratio();
  r.jump_rms_ratio = jump.rms_ratio();
  r.nodal_increment_ratio = nodal.increment_ratio();
  return r;
}

}  // namespace finverse::cfd::validation
