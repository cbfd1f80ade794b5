// Chordwise and spanwise profile lines of the fin (see fin_profiles.hpp; paper Fig. 15(a)).
#include "report/fin_profiles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "core/error.hpp"

namespace finverse::report {

namespace {

void check_rest(const NdArray<double>& rest) {
  if (rest.rank() != 2 || rest.dim(1) != 3 || rest.dim(0) < 3)
    throw Error("profile line: expected at least 3 rest points [nv,3], got " + shape_string(rest.shape));
}

// Nodes with |coord(across) - at| <= band, widening the band from 1 % of the extent until 3 are
// found; sorted by coord(along).
LineNodes line_near(const NdArray<double>& rest, std::size_t across, double at, std::size_t along) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t i = 0; i < rest.dim(0); ++i) lo = std::min(lo, rest(i, across)), hi = std::max(hi, rest(i, across));
  const double extent = std::max(hi - lo, 1e-12);
  LineNodes line;
  for (double band = 0.01 * extent; band <= 2 * extent; band *= 1.5) {
    line.nodes.clear();
    for (std::size_t i = 0; i < rest.dim(0); ++i)
      if (std::abs(rest(i, across) - at) <= band) line.nodes.push_back(i);
    if (line.nodes.size() >= 3) break;
  }
  if (line.nodes.size() < 3) throw Error("profile line: fewer than 3 nodes near the line");
  std::stable_sort(line.nodes.begin(), line.nodes.end(),
                   [&](std::size_t a, std::size_t b) { return rest(a, along) < rest(b, along); });
  for (auto n : line.nodes) line.coordinate.push_back(rest(n, along));
  return line;
}

}  // namespace

LineNodes chordwise_line(const NdArray<double>& rest) {
  check_rest(rest);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t i = 0; i < rest.dim(0); ++i) lo = std::min(lo, rest(i, 2)), hi = std::max(hi, rest(i, 2));
  return line_near(rest, 2, 0.5 * (lo + hi), 0);
}

LineNodes spanwise_line(const NdArray<double>& rest, double chord, double fraction) {
  check_rest(rest);
  if (!(chord > 0)) throw Error("profile line: the chord must be positive");
  double root = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < rest.dim(0); ++i) root = std::min(root, rest(i, 0));
  return line_near(rest, 0, root + fraction * chord, 2);
}

std::vector<double> lateral_profile(const NdArray<double>& points, const LineNodes& line, std::size_t frame) {
  if (points.rank() != 3 || points.dim(2) != 3 || frame >= points.dim(0))
    throw Error("lateral profile: frame " + std::to_string(frame) + " outside points " + shape_string(points.shape));
  std::vector<double> y;
  for (auto n : line.nodes) {
    if (n >= points.dim(1)) throw Error("lateral profile: node " + std::to_string(n) + " outside the points");
    y.push_back(points(frame, n, 1));
  }
  return y;
}

std::size_t midway_frame(const std::vector<double>& series) {
  if (series.empty()) return 0;
  const auto [lo, hi] = std::minmax_element(series.begin(), series.end());
  const double mid = 0.5 * (*lo + *hi);
  std::size_t best = 0;
  for (std::size_t f = 1; f < series.size(); ++f)
    if (std::abs(series[f] - mid) < std::abs(series[best] - mid)) best = f;
  return best;
}

}  // namespace finverse::report
