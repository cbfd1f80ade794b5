// Carrying a surface motion onto the structural mesh nodes (DESIGN.md section 1: fin-mesh writes
// motion.h5, "the reconstructed motion carried onto the mesh nodes"). Each mesh node is bound, in
// the rest configuration, to the closest point of the source surface (a triangle and barycentric
// weights); per frame the node follows that point. An affine combination of rigidly moved
// vertices is the rigidly moved point, so a rigid motion is carried exactly.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "core/nd_array.hpp"

namespace finverse::mesh {

struct SurfaceBinding {
  std::vector<std::array<int, 3>> vertices;     // source vertices of the triangle each node binds to
  std::vector<std::array<double, 3>> weights;   // barycentric weights (sum 1, each >= 0)
  double max_distance = 0;                      // largest node-to-surface distance at rest, metres
};

// source_points [nv,3], source_triangles [ntri,3], targets [n,3].
SurfaceBinding bind_to_surface(const NdArray<double>& source_points, const NdArray<std::int32_t>& source_triangles,
                               const NdArray<double>& targets);

// source_frames [nf,nv,3] -> [nf,n,3].
NdArray<double> carry_motion(const SurfaceBinding& b, const NdArray<double>& source_frames);

// Node velocities [nf,n,3] by second-order central differences in time; periodic wrap-around when
// `period` is given and the samples are uniform and cover exactly one period, else second-order
// one-sided differences at the ends.
NdArray<double> velocities(const std::vector<double>& time, const NdArray<double>& frames, std::optional<double> period);

}  // namespace finverse::mesh
