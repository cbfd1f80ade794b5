// The nodal state (positions and rotations) of a shape known only by its node positions: the
// base x_t of the quasi-static increment, eq. (2), when x_t is the reconstructed (tracked) shape.
// Video gives positions; the shell and beam nodes also carry rotations, which are taken as the
// least-squares rigid rotation (fem::fit_rigid_rotation, Kabsch) of each node's element 1-ring
// (the node and every node it shares an element with) from the reference onto the current
// positions. That is exact for a rigid motion and the local tangent rotation, to O(h), for a
// smooth deformation; on a line of beam nodes the spin about the line is not observable and is
// taken as zero (fit_rigid_rotation's collinear rule).
#pragma once

#include <vector>

#include "fem/model.hpp"
#include "fem/nodal_state.hpp"

namespace finverse::fit {

// For each node, the other nodes it shares an element with (ascending).
std::vector<std::vector<int>> node_one_rings(const fem::Model& model);

class StateFromPositions {
 public:
  explicit StateFromPositions(const fem::Model& model);
  // Throws InvalidInput unless positions has one finite entry per node.
  fem::NodalState operator()(const std::vector<fem::Vec3>& positions) const;
  int node_count() const { return static_cast<int>(reference_.size()); }

 private:
  std::vector<fem::Vec3> reference_;
  std::vector<std::vector<int>> ring_;  // node itself first, then its 1-ring
};

// One-off form of the above.
fem::NodalState state_from_positions(const fem::Model& model, const std::vector<fem::Vec3>& positions);

}  // namespace finverse::fit
