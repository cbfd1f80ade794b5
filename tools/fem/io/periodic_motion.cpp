// Periodic repetition of a sampled motion (see periodic_motion.hpp).
#include "fem/io/periodic_motion.hpp"

#include <cmath>
#include <vector>

#include "fem/errors.hpp"

namespace finverse::fem::io {

bool needs_periodic_extension(const stage::Motion& m, double t_begin, double t_end) {
  if (!m.period || m.time.data.empty()) return false;
  const double tol = 1e-12 * std::max(1.0, *m.period);
  return t_begin < m.time.data.front() - tol || t_end > m.time.data.back() + tol;
}

stage::Motion periodic_extension(const stage::Motion& m, double t_begin, double t_end) {
  if (!m.period || !(*m.period > 0)) throw InvalidInput("periodic extension: the motion has no period T");
  const double T = *m.period, t0 = m.time.data.front();
  const std::size_t nf = m.time.data.size(), nv = m.points.dim(1);
  const int k0 = static_cast<int>(std::floor((t_begin - t0) / T)), k1 = static_cast<int>(std::ceil((t_end - t0) / T));
  stage::Motion e;
  e.period = m.period;
  std::vector<double> times;
  std::vector<double> points;
  for (int k = k0; k <= k1; ++k)
    for (std::size_t f = 0; f < nf; ++f) {
      const double t = m.time.data[f] + k * T;
      if (!times.empty() && t <= times.back() + 1e-9 * T) continue;
      times.push_back(t);
      points.insert(points.end(), m.points.data.begin() + static_cast<std::ptrdiff_t>(f * nv * 3),
                    m.points.data.begin() + static_cast<std::ptrdiff_t>((f + 1) * nv * 3));
    }
  e.time = NdArray<double>({times.size()}, times);
  e.points = NdArray<double>({times.size(), nv, 3}, points);
  return e;
}

}  // namespace finverse::fem::io
