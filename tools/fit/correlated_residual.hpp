// How the residual at the optimum is correlated, and the parameter covariance that follows
// (issue 45, deliverable 6: intervals that know the model is not exact). The residual is taken as
// one stationary field over the fin shared by every sample and component (the intrinsic
// coregionalisation model of geostatistics): Cov = K (x) R, K the channels' (sample x component)
// covariance at the same node, R_ij = exp(-d_ij / l) with l where the empirical correlation falls
// to 1/e. The covariance of the estimate is the sandwich (J^T J)^-1 J^T (K (x) R) J (J^T J)^-1,
// with (tr K)^2 (tr R)^2 / (tr K^2 tr R^2) effective residuals for the t quantile. A misfit that
// repeats its shape at every sample counts once, not once per sample. A white residual gives
// l = 0 and the usual covariance back. Why: docs/studies/fit_model_misfit.md.
#pragma once

#include <Eigen/Core>

#include "fit/residual_layout.hpp"

namespace finverse::fit {

struct ResidualCorrelation {
  double length = 0;               // l of R; 0: white
  double spacing = 0;              // median nearest-neighbour distance of the layout's nodes
  double neighbour = 0;            // empirical correlation at the nearest-neighbour distance
  double effective_residuals = 0;  // (tr K)^2 (tr R)^2 / (tr K^2 tr R^2)
  double effective_channels = 0;   // (tr K)^2 / tr K^2: 3 x samples when they err independently
  Eigen::MatrixXd channels;        // K: 3 blocks x 3 blocks, rows sample-major as the residual
  // The correlation at the nearest-neighbour distance is at least `systematic_correlation`:
  // neighbouring residuals err alike, so the misfit is the model's, not the data's noise.
  bool systematic = false;
};

// Throws InvalidInput when r's length is not 3 * blocks * points.cols().
ResidualCorrelation estimate_residual_correlation(const Eigen::VectorXd& r, const ResidualLayout& layout,
                                                  double systematic_correlation = 0.5);

// J^T (K (x) R) J with K = correlation.channels and R the exponential of correlation.length
// (the identity when it is 0). jacobian: m x n, rows as r.
Eigen::MatrixXd correlated_gram(const Eigen::MatrixXd& jacobian, const ResidualLayout& layout,
                                const ResidualCorrelation& correlation);

// K comes from a residual r = (I - P) misfit that lacks the misfit's part in span(Q) (Q: m x k,
// orthonormal columns: the fitted sensitivities); for a smooth misfit that part is far more than
// k/m of it. The factor tr(K (x) R) / (tr(K (x) R) - tr(Q^T (K (x) R) Q)) restores the scale
// that the residual's expected sum of squares under K (x) R implies (REML's correction).
double span_share_correction(const Eigen::MatrixXd& q, const ResidualLayout& layout,
                             const ResidualCorrelation& correlation);

}  // namespace finverse::fit
