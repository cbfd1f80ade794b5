// The W-shape measures alpha1, alpha2, d1, d2 of a spanwise profile (see w_shape.hpp; Fig. 15(b)).
#include "report/w_shape.hpp"

#include <cmath>
#include <numbers>

#include "core/error.hpp"

namespace finverse::report {

namespace {

// One half: nodes [first, last], the tip at `tip`; s the side the edges lead to (+1 or -1).
void measure_half(const std::vector<double>& z, const std::vector<double>& y, std::size_t first, std::size_t last,
                  std::size_t tip, double s, double chord, double& alpha_deg, double& d) {
  std::size_t lag = tip;
  for (std::size_t i = first; i <= last; ++i)
    if (s * (y[tip] - y[i]) > s * (y[tip] - y[lag])) lag = i;
  const double dy = s * (y[tip] - y[lag]);
  d = dy / chord;
  alpha_deg = lag == tip ? 0.0 : std::atan2(dy, std::abs(z[tip] - z[lag])) * 180.0 / std::numbers::pi;
}

}  // namespace

WShape w_shape(const std::vector<double>& z, const std::vector<double>& y, double chord) {
  const std::size_t n = z.size();
  if (n < 3 || y.size() != n) throw Error("W shape: expected at least 3 nodes with z and y of equal length");
  if (!(chord > 0)) throw Error("W shape: the chord must be positive");
  for (std::size_t i = 1; i < n; ++i)
    if (z[i] < z[i - 1]) throw Error("W shape: the spanwise coordinates are not sorted");
  const double z_mid = 0.5 * (z.front() + z.back());
  // The lateral position at mid-span, interpolated between the nodes around it.
  std::size_t k = 1;
  while (k < n - 1 && z[k] < z_mid) ++k;
  const double w = z[k] > z[k - 1] ? (z_mid - z[k - 1]) / (z[k] - z[k - 1]) : 0.0;
  const double y_mid = (1 - w) * y[k - 1] + w * y[k];
  // Halves: nodes below and above mid-span (the node at mid-span, if any, in both).
  std::size_t upper_first = 0;
  while (upper_first < n && z[upper_first] < z_mid) ++upper_first;
  std::size_t lower_last = n - 1;
  while (lower_last > 0 && z[lower_last] > z_mid) --lower_last;
  // The edges lead on the side where their mean sits relative to mid-span.
  const double s = 0.5 * (y.front() + y.back()) >= y_mid ? 1.0 : -1.0;
  WShape out;
  measure_half(z, y, upper_first, n - 1, n - 1, s, chord, out.alpha1_deg, out.d1);
  measure_half(z, y, 0, lower_last, 0, s, chord, out.alpha2_deg, out.d2);
  return out;
}

}  // namespace finverse::report
