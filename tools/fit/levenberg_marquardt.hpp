// The local least-squares polish after the GA (DESIGN.md section 5.4): Levenberg-Marquardt on
// S(z) = |r(z)|^2 in the scaled variables z, steps projected onto the box, bounds that the
// gradient pushes against held fixed. The Jacobian dr/dz comes from finite differences with its
// columns evaluated in parallel; the polish needs tens of evaluations where a GA needs
// thousands. The result carries the Jacobian at the returned point for the uncertainty.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>

#include "fit/parameter_space.hpp"
#include "fit/residual_function.hpp"

namespace finverse::fit {

struct LmOptions {
  int max_evaluations = 0;            // 0 = 6 (n + 1); the final Jacobian is always within it
  double reduction_tolerance = 1e-4;  // stop when an accepted step lowers S by less than this fraction
  double step_tolerance = 1e-7;       // stop when a step is shorter than this (scaled, max-norm)
  double fd_step = 1e-4;              // finite-difference step, fraction of each scaled bound width
  bool central = false;               // central differences: twice the evaluations, O(h^2) error
  double initial_damping = 1e-3;      // Marquardt lambda (relative to diag(J^T J))
  int threads = 2;                    // for the Jacobian columns
  // One line per tried step (|r|^2, damping, evaluations so far): a refit of model runs takes minutes.
  std::function<void(const std::string&)> progress;
  // Called with the scaled point after each accepted step, before its Jacobian: the objective may
  // move its reference solutions there (ResidualFunction::expect_near), so that the Jacobian's
  // columns, a small step away, are cheap.
  std::function<void(const Eigen::VectorXd&)> moved;
};

struct LmResult {
  Eigen::VectorXd z;          // scaled optimum
  Eigen::VectorXd residuals;  // r(z)
  Eigen::MatrixXd jacobian;   // dr/dz at z (empty if the start point failed)
  double sum_of_squares = 0;  // |r|^2
  double objective = 0;       // distance objective at z
  long evaluations = 0;
  int iterations = 0;         // accepted steps
  std::string stop_reason;
  double wall_seconds = 0;
};

// dr/dz at z by finite differences (steps inward at a bound); r0 = r(z). A column whose
// evaluation fails is left zero (the direction then reads as insensitive). Adds to *evaluations.
Eigen::MatrixXd finite_difference_jacobian(const ParameterSpace& space, const ResidualFunction& function,
                                           const Eigen::VectorXd& z, const Eigen::VectorXd& r0,
                                           double fd_step, bool central, int threads,
                                           long* evaluations);

// From z0 (clamped into the box).
LmResult levenberg_marquardt(const ParameterSpace& space, const ResidualFunction& function,
                             const Eigen::VectorXd& z0, const LmOptions& options = {});

}  // namespace finverse::fit
