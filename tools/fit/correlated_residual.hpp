// How the residual at the optimum is correlated in space, and the parameter covariance that
// follows (issue 45, deliverable 6: intervals that know the model is not exact). The residual is
// taken as a stationary field per sample and component with R_ij = exp(-d_ij / l), l where its
// empirical correlation falls to 1/e; the covariance is the sandwich
//     C = (J^T J)^-1 J^T (s^2 R) J (J^T J)^-1,   s^2 = |r|^2 / m,
// with (tr R)^2 / tr(R^2) effective residuals for the t quantile. A white residual gives l = 0
// and the usual covariance back. Why and what it does: docs/studies/fit_model_misfit.md.
#pragma once

#include <Eigen/Core>

#include "fit/residual_layout.hpp"

namespace finverse::fit {

struct ResidualCorrelation {
  double length = 0;               // l of R; 0: white
  double spacing = 0;              // median nearest-neighbour distance of the layout's nodes
  double neighbour = 0;            // empirical correlation at the nearest-neighbour distance
  double effective_residuals = 0;  // (tr R)^2 / tr(R^2)
  // The correlation at the nearest-neighbour distance is at least `systematic_correlation`:
  // neighbouring residuals err alike, so the misfit is the model's, not the data's noise.
  bool systematic = false;
};

// Throws InvalidInput when r's length is not 3 * blocks * points.cols().
ResidualCorrelation estimate_residual_correlation(const Eigen::VectorXd& r, const ResidualLayout& layout,
                                                  double systematic_correlation = 0.5);

// J^T R J for the exponential R of the given length, block by block and component by component
// (R couples only the same component of the same sample). jacobian: m x n, rows as r.
Eigen::MatrixXd correlated_gram(const Eigen::MatrixXd& jacobian, const ResidualLayout& layout, double length);

}  // namespace finverse::fit
