// Root pitch of every fin ray over time (seed paper Fig. 12: U-shaped amplitude and W-shaped phase
// across the rays): the angle of the ray's proximal segment out of the x-z plane, i.e. about the
// spanwise axis, atan2(dy, |(dx, dz)|) in degrees. The segment runs from the ray's first vertex to
// the vertex a fifth of the way along it, so one noisy vertex near the root does not dominate.
#pragma once

#include <cstdint>
#include <vector>

#include "core/nd_array.hpp"

namespace finverse::report {

// points: [nf,nv,3]; ray_offsets [nrays+1] into ray_vertices (kinematics.h5 template/ray_*).
// Returns [nrays][nf] in degrees. Throws finverse::Error for rays outside the points.
std::vector<std::vector<double>> root_pitch_deg(const NdArray<double>& points, const NdArray<std::int32_t>& ray_offsets,
                                                const NdArray<std::int32_t>& ray_vertices);

}  // namespace finverse::report
