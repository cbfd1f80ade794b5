// The coupled interface unknown of the implicit partitioned FSI (seed paper section 2.3, steps
// 1-5): the wet surface's displacement X and velocity V stacked as one vector z = [X; V], the
// quantity the accelerations relax (the paper relaxes X and V with the same factor, step 3).
// X should be the displacement from the reference configuration, not the absolute position: the
// relative convergence measure divides by |X|, which an absolute coordinate offset would inflate.
// A layout with n_velocity = 0 couples displacement only (as the linear test problems do).
#pragma once

#include <Eigen/Core>

namespace finverse::fsi {

struct InterfaceLayout {
  Eigen::Index n_position = 0;  // entries of the displacement block X (dim x surface nodes)
  Eigen::Index n_velocity = 0;  // entries of the velocity block V: 0 or n_position

  [[nodiscard]] Eigen::Index size() const { return n_position + n_velocity; }

  // Throws finverse::Error unless n_position > 0 and n_velocity is 0 or n_position.
  void validate() const;
  // Throws finverse::Error naming `what` unless z.size() == size() and z is finite.
  void check(const Eigen::VectorXd& z, const char* what) const;

  [[nodiscard]] Eigen::VectorXd stack(const Eigen::VectorXd& x, const Eigen::VectorXd& v) const;
  [[nodiscard]] auto position(const Eigen::VectorXd& z) const { return z.head(n_position); }
  [[nodiscard]] auto velocity(const Eigen::VectorXd& z) const { return z.tail(n_velocity); }
};

}  // namespace finverse::fsi
