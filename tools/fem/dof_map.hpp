// Numbering of the unknowns: global DOF g = 6 * node + k (k = ux uy uz rx ry rz) maps to an
// equation number, or to -1 when the DOF is prescribed or touched by no element (a node of a
// plane-strain solid has no rotational stiffness; leaving such DOFs in would make the matrix
// singular for no physical reason).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "fem/model.hpp"

namespace finverse::fem {

class DofMap {
 public:
  explicit DofMap(const Model& model);

  int total() const { return static_cast<int>(equation_.size()); }
  int free() const { return static_cast<int>(free_to_global_.size()); }
  int equation(int global_dof) const { return equation_[global_dof]; }
  bool is_prescribed(int global_dof) const { return prescribed_[global_dof]; }
  bool is_active(int global_dof) const { return active_[global_dof]; }
  const std::vector<int>& free_to_global() const { return free_to_global_; }

  Eigen::VectorXd gather_free(const Eigen::VectorXd& full) const;
  Eigen::VectorXd scatter_free(const Eigen::VectorXd& free) const;  // zeros elsewhere

 private:
  std::vector<int> equation_;
  std::vector<int> free_to_global_;
  std::vector<bool> prescribed_, active_;
};

}  // namespace finverse::fem
