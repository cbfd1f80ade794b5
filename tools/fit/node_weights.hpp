// Node weights w_i of the residuals r_i = sqrt(w_i) (dx_FE^i - dx_target^i) of eqs. (1) and (2)
// (residual_function.hpp). The paper weights every point alike on a uniform mesh and suggests
// weights for a non-uniform one; the default here is each node's share of the structure:
//   shell nodes   a third of the area of every triangle (element of >= 3 nodes: its polygon
//                 area shared equally) they belong to;
//   beam-only     nodes on no shell (a ray beyond the membrane) half the length of each beam
//                 they end, times the mean shell edge length: a strip one element wide, so that
//                 areas and lengths are commensurate (no shells at all: the length share alone);
// normalised to mean 1 over the compared nodes; prescribed nodes (root, leading edge) weigh 0 and
// are left out of the residuals, since their motion is imposed, not predicted.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "fem/model.hpp"

namespace finverse::fit {

Eigen::VectorXd default_node_weights(const fem::Model& model, const std::vector<int>& prescribed);

// Checks caller-given weights (one per node, finite, >= 0, some > 0 off the prescribed nodes;
// InvalidInput naming `what` otherwise) and zeroes the prescribed nodes'.
Eigen::VectorXd checked_node_weights(const Eigen::VectorXd& weights, int node_count,
                                     const std::vector<int>& prescribed, const std::string& what);

// The nodes with w_i > 0, ascending: those the residuals compare.
std::vector<int> compared_nodes(const Eigen::VectorXd& weights);

// Their reference positions, one column per compared node (ResidualLayout::points).
Eigen::Matrix3Xd compared_points(const fem::Model& model, const std::vector<int>& nodes);

}  // namespace finverse::fit
