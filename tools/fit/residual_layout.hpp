// Where each residual sits (issue 45, deliverable 6): the objectives' residuals are sample-major
// blocks (instants, frames or load levels), each the same compared nodes in the same order, three
// components per node. The nodes' reference positions let the uncertainty estimate how the
// residual is correlated in space (correlated_residual.hpp).
#pragma once

#include <Eigen/Core>

namespace finverse::fit {

struct ResidualLayout {
  int blocks = 0;           // samples; residual_count() = 3 * blocks * points.cols()
  Eigen::Matrix3Xd points;  // the compared nodes' reference positions, in residual order
};

}  // namespace finverse::fit
