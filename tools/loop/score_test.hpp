// The score (Lagrange-multiplier) test of a candidate effect at the current fit (issue 34;
// DESIGN.md section 5.6). At the optimum the residual r (m entries, prediction - data) is
// orthogonal to the fitted parameters' sensitivities J (m x n); a candidate with sensitivity
// columns S (m x q: finite differences of the prediction in its main parameters, one model run
// each) can only explain what is left once S is projected off span(J):
//     S_perp = (I - Q Q^T) S,  Q an orthonormal basis of span(J),
//     LM = r^T S_perp (S_perp^T S_perp)^+ S_perp^T r / s^2,  s^2 = |r|^2 / (m - n),
// which is chi^2 with q degrees of freedom when the candidate is absent. A candidate inside
// span(J) (what a refit of the current parameters already absorbs) scores 0. The one-step
// estimate  delta = -(S_perp^T S_perp)^+ S_perp^T r  starts its refit.
//
// A residual that is the model's misfit is not white: smooth in space and repeated from frame to
// frame, it makes every candidate significant under s^2 I (issue 45, deliverable 4). Given where
// the residuals sit, a systematic residual (fit/correlated_residual.hpp) replaces s^2 I by its
// estimated covariance V = K (x) R, and the statistic becomes the robust score
//     LM = g^T (S_perp^T V S_perp)^+ g,  g = S_perp^T r,
// referred to F(q, N_eff - n) q (N_eff the residual's effective count), not chi^2_q: V is
// estimated from few independent pieces.
#pragma once

#include <Eigen/Core>

#include "fit/residual_layout.hpp"

namespace finverse::loop {

struct ScoreResult {
  double statistic = 0;      // LM
  int degrees_of_freedom = 0;
  double p_value = 1;        // chi^2_q tail
  double projected_fraction = 0;  // |S_perp|_F / |S|_F: 0 when S lies in span(J)
  Eigen::VectorXd step;      // one-step estimate of the candidate's parameters
  bool correlated = false;   // the residual was systematic: the robust statistic
  double effective_residuals = 0;  // N_eff when correlated
};

// The orthonormal basis Q of span(J) (rank by a relative tolerance on the pivoted QR).
Eigen::MatrixXd orthonormal_basis(const Eigen::MatrixXd& jacobian, double tolerance = 1e-10);

// q from s.cols(). Columns whose projection is below in_span_tolerance times their norm count
// as inside span(J). layout (optional): where each residual sits; a systematic residual then gives
// the robust statistic. data (> 0): the data among r's rows (structural zeros left out) for s^2;
// 0: every row. Throws InvalidInput on row counts that differ or m <= n.
ScoreResult score_test(const Eigen::VectorXd& r, const Eigen::MatrixXd& basis, int fitted_parameters,
                       const Eigen::MatrixXd& s, double in_span_tolerance = 1e-8,
                       const fit::ResidualLayout* layout = nullptr, double data = 0);

// Upper tail of chi^2 with q degrees of freedom at x.
double chi2_tail(double x, int q);

}  // namespace finverse::loop
