// The residual of closing the loop (issue 34, DESIGN.md section 5.6): model prediction minus
// reconstruction, per node and frame, on one mesh and one time base. Stored as a matrix with
// one row per node component (row 3 i + c: node i, axis c) and one column per frame, the layout
// the POD (residual_modes.hpp) decomposes directly.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace finverse::loop {

// A node motion sampled in time: positions[frame] is a (3 nv) vector, node-major.
struct SampledMotion {
  std::string source;  // file named in messages
  std::vector<double> times;
  std::vector<Eigen::VectorXd> positions;
  int node_count() const { return positions.empty() ? 0 : static_cast<int>(positions[0].size() / 3); }
};

struct ResidualField {
  std::vector<double> times;
  Eigen::MatrixXd values;  // [3 nv, nf]: prediction - reconstruction
  int node_count() const { return static_cast<int>(values.rows() / 3); }
  int frame_count() const { return static_cast<int>(values.cols()); }
  Eigen::Vector3d at(int node, int frame) const { return values.block<3, 1>(3 * node, frame); }
};

// prediction - reconstruction. Refuses (InvalidInput naming both sources) different node counts,
// a node count other than mesh_nodes, different frame counts, or frame times that differ by more
// than time_tolerance times the frame spacing (different time bases are not interpolated: a
// residual between shifted samples would report the shift as model error).
ResidualField residual_field(const SampledMotion& prediction, const SampledMotion& reconstruction, int mesh_nodes,
                             double time_tolerance = 1e-6);

}  // namespace finverse::loop
