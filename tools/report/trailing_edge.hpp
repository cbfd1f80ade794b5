// The trailing-edge feature points of the seed paper's Fig. 14 and their lateral excursion: point 1
// near the dorsal tip, point 2 at mid-span, point 3 near the ventral tip (z is dorsal, x
// downstream: DESIGN.md section 3). Each is the most downstream rest vertex of its spanwise band
// (top fifth, middle tenth, bottom fifth of the span; ties go to the tip or the middle), so the same rule picks comparable points on
// the template's vertices (truth, kinematics) and on the mesh's nodes (motion, fsi). The graded
// number is the peak-to-peak lateral (y) displacement over the record, in chords (the paper:
// 1.10c, 0.90c, 1.07c reconstructed against 1.01c, 0.85c, 0.96c by its FSI).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "core/nd_array.hpp"

namespace finverse::report {

// rest: [nv,3]. Returns the vertex index of points 1, 2, 3. Throws finverse::Error for an empty
// or flat (zero span) point set.
std::array<std::size_t, 3> trailing_edge_points(const NdArray<double>& rest);

// points: [nf,nv,3]; the node's coordinate `axis` (1 = lateral) at every frame.
std::vector<double> node_series(const NdArray<double>& points, std::size_t node, std::size_t axis = 1);

// max - min of a series (0 for an empty one).
double peak_to_peak(const std::vector<double>& series);

}  // namespace finverse::report
