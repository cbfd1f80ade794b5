// Configuration of the structure: current position and rotation of every node.
//
// Translations are additive (x = X + u); rotations are kept as rotation matrices and updated
// multiplicatively with spatial spins, R <- exp(skew(dw)) R, so that no rotation-vector
// singularity at |theta| = 2 pi exists and no additive rotation error accumulates. Global vectors
// (increments, velocities, forces) are laid out 6 per node: ux uy uz wx wy wz, the last three
// being spatial spins / angular velocities / moments.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "fem/rotation.hpp"

namespace finverse::fem {

inline constexpr int kDofsPerNode = 6;

struct NodalState {
  std::vector<Vec3> position;  // x, current
  std::vector<Mat3> rotation;  // R, current (identity in the reference configuration)

  int node_count() const { return static_cast<int>(position.size()); }
  // Applies a full-length (6 per node) increment: x += du, R <- exp(dw) R.
  void apply_increment(const Eigen::VectorXd& increment);
};

}  // namespace finverse::fem
