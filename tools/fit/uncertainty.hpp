// Uncertainty and identifiability at the optimum (DESIGN.md section 5.4, issue 31): the
// Gauss-Newton covariance C = s^2 (J^T J)^+ in the scaled variables, s^2 = |r|^2 / (m - n), from
// the polish Jacobian J = dr/dz. The pseudo-inverse comes from the SVD of J, so a (near)
// singular direction gives infinite standard errors instead of a huge, confident-looking number.
// A parameter is reported identified only when its direction is not singular, it is not at a
// bound, its 95 % interval reaches no bound and spans at most a decade (log10) or the bounds'
// width (linear).
//
// With the residual's layout, a spatially correlated (systematic) misfit gives the sandwich
// covariance of correlated_residual.hpp, verdicts prefixed "model misfit dominates: ", and
// "insensitive" for a parameter whose whole range moves the residual less than that misfit.
#pragma once

#include <Eigen/Core>

#include "fit/fit_result.hpp"
#include "fit/parameter_space.hpp"
#include "fit/residual_layout.hpp"

namespace finverse::fit {

struct UncertaintyOptions {
  double singular_tolerance = 1e-6;  // singular values below this times the largest are zero
  double singular_share = 0.01;      // a parameter whose squared share of the null space exceeds
                                     // this is insensitive
  double bound_tolerance = 1e-3;     // at a bound: within this fraction of the scaled range
  double confidence = 0.95;
  // Correlation of neighbouring residuals from which the misfit counts as systematic.
  double systematic_correlation = 0.5;
};

// z: the scaled optimum; r = r(z) (m entries); jacobian: m x n; layout: where each residual sits
// (null: independent residuals assumed).
Uncertainty compute_uncertainty(const ParameterSpace& space, const Eigen::VectorXd& z, const Eigen::VectorXd& r,
                                const Eigen::MatrixXd& jacobian, const UncertaintyOptions& options = {},
                                const ResidualLayout* layout = nullptr);

}  // namespace finverse::fit
