// How far one motion of the fin is from another (issue 33 "Scores": FSI motion vs truth motion,
// mean vertex distance <= 1 % c): the truth, recorded on the template's vertices, is first carried
// onto the mesh's nodes by the same barycentric binding fin-mesh uses (mesh/motion_transfer.hpp);
// then at every frame of the first motion inside the second's time span the second is interpolated
// linearly in time and the node distances are averaged over nodes and frames.
#pragma once

#include "core/nd_array.hpp"
#include "core/stage_files.hpp"

namespace finverse::report {

// The truth's motion [nf,nv,3] on the mesh's nodes.
NdArray<double> truth_on_mesh(const stage::Truth& truth, const stage::Mesh& mesh);

// Mean |a - b(t_a)| [m] over a's frames inside b's time span and over the nodes; NaN when no frame
// of a lies inside b's span. Throws finverse::Error for different node counts.
double mean_node_distance(const NdArray<double>& a_time, const NdArray<double>& a_points, const NdArray<double>& b_time,
                          const NdArray<double>& b_points);

}  // namespace finverse::report
