// The two lines of the seed paper's Fig. 15(a) along which the fin's deformation is profiled: the
// chordwise line at mid-span (a horizontal line, seen from the top) and the spanwise line 0.8
// chord downstream of the fin root (a vertical line, seen from the back). A line is the set of
// rest nodes within a thin band around it, sorted along it; the band widens until it holds at
// least 3 nodes, so it works on any triangulation of the fin.
#pragma once

#include <cstddef>
#include <vector>

#include "core/nd_array.hpp"

namespace finverse::report {

struct LineNodes {
  std::vector<std::size_t> nodes;  // sorted along the line
  std::vector<double> coordinate;  // the rest coordinate along the line (x or z) [m]
};

// rest: [nv,3]. Nodes near z = mid-span, sorted by x.
LineNodes chordwise_line(const NdArray<double>& rest);
// Nodes near x = x_root + fraction * chord, sorted by z (x_root: the most upstream rest node).
LineNodes spanwise_line(const NdArray<double>& rest, double chord, double fraction = 0.8);

// points: [nf,nv,3]; the lateral (y) position of the line's nodes at frame f.
std::vector<double> lateral_profile(const NdArray<double>& points, const LineNodes& line, std::size_t frame);

// The frame at mid-stroke: where the series is closest to the middle of its range (the fin moves
// fastest there and the paper's "W" is fully developed). 0 for an empty series.
std::size_t midway_frame(const std::vector<double>& series);

}  // namespace finverse::report
