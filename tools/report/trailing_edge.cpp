// Trailing-edge feature points and peak-to-peak excursion (see trailing_edge.hpp; paper Fig. 14).
#include "report/trailing_edge.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace finverse::report {

std::array<std::size_t, 3> trailing_edge_points(const NdArray<double>& rest) {
  if (rest.rank() != 2 || rest.dim(1) != 3 || rest.dim(0) == 0)
    throw Error("trailing-edge points: expected rest points [nv,3], got " + shape_string(rest.shape));
  const std::size_t nv = rest.dim(0);
  double zmin = std::numeric_limits<double>::infinity(), zmax = -zmin;
  for (std::size_t i = 0; i < nv; ++i) zmin = std::min(zmin, rest(i, 2)), zmax = std::max(zmax, rest(i, 2));
  const double h = zmax - zmin;
  if (!(h > 0)) throw Error("trailing-edge points: the fin has no span (all z equal)");
  // Bands as fractions of the span from the ventral edge: point 1 dorsal, 2 middle, 3 ventral.
  const std::array<std::array<double, 2>, 3> bands{{{0.8, 1.0}, {0.45, 0.55}, {0.0, 0.2}}};
  std::array<std::size_t, 3> out{};
  for (std::size_t p = 0; p < 3; ++p) {
    double best = -std::numeric_limits<double>::infinity();
    bool found = false;
    // Among equally downstream vertices: the outermost for the tips, the most central for point 2.
    const double target = p == 0 ? 1.0 : (p == 1 ? 0.5 : 0.0);
    double best_offset = 0;
    for (std::size_t i = 0; i < nv; ++i) {
      const double f = (rest(i, 2) - zmin) / h;
      if (f < bands[p][0] || f > bands[p][1]) continue;
      const double x = rest(i, 0), offset = std::abs(f - target), tie = 1e-9 * h;
      if (!found || x > best + tie || (x >= best - tie && offset < best_offset))
        best = std::max(best, x), best_offset = offset, out[p] = i, found = true;
    }
    if (!found) throw Error("trailing-edge points: no vertex in the spanwise band of point " + std::to_string(p + 1));
  }
  return out;
}

std::vector<double> node_series(const NdArray<double>& points, std::size_t node, std::size_t axis) {
  if (points.rank() != 3 || points.dim(2) != 3 || node >= points.dim(1) || axis > 2)
    throw Error("node series: node " + std::to_string(node) + " outside points " + shape_string(points.shape));
  std::vector<double> s(points.dim(0));
  for (std::size_t f = 0; f < s.size(); ++f) s[f] = points(f, node, axis);
  return s;
}

double peak_to_peak(const std::vector<double>& series) {
  if (series.empty()) return 0;
  const auto [lo, hi] = std::minmax_element(series.begin(), series.end());
  return *hi - *lo;
}

}  // namespace finverse::report
