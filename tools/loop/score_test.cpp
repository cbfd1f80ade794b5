// Score test of a candidate off span(J) (score_test.hpp).
#include "loop/score_test.hpp"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <boost/math/distributions/fisher_f.hpp>
#include <cmath>
#include <string>

#include "fit/correlated_residual.hpp"
#include "loop/errors.hpp"

namespace finverse::loop {

Eigen::MatrixXd orthonormal_basis(const Eigen::MatrixXd& jacobian, double tolerance) {
  if (jacobian.cols() == 0) return Eigen::MatrixXd(jacobian.rows(), 0);
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(jacobian);
  qr.setThreshold(tolerance);
  const Eigen::Index rank = qr.rank();
  const Eigen::MatrixXd q = qr.householderQ() * Eigen::MatrixXd::Identity(jacobian.rows(), rank);
  return q;
}

double chi2_tail(double x, int q) {
  if (!(x > 0)) return 1.0;
  // Regularised upper incomplete gamma Q(q/2, x/2) by its series / continued fraction.
  const double a = 0.5 * q, z = 0.5 * x;
  if (z < a + 1) {
    double sum = 1.0 / a, term = sum;
    for (int n = 1; n < 500; ++n) {
      term *= z / (a + n);
      sum += term;
      if (term < sum * 1e-15) break;
    }
    return std::max(0.0, 1.0 - sum * std::exp(-z + a * std::log(z) - std::lgamma(a)));
  }
  double b = z + 1 - a, c = 1e300, d = 1 / b, h = d;
  for (int i = 1; i < 500; ++i) {
    const double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (std::abs(d) < 1e-300) d = 1e-300;
    c = b + an / c;
    if (std::abs(c) < 1e-300) c = 1e-300;
    d = 1 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1) < 1e-15) break;
  }
  return std::exp(-z + a * std::log(z) - std::lgamma(a)) * h;
}

namespace {

// The robust statistic g^T (S_perp^T V S_perp)^+ g when the residual is systematic (header). V is
// estimated from the residual with the candidate fitted (r - S_perp coef): under the null that
// is r, and a present effect does not inflate V and hide itself. Its scale is corrected for the
// misfit's share in span(J, S) (fit::span_share_correction).
void robust_score(const Eigen::VectorXd& r, const Eigen::VectorXd& explained, const Eigen::MatrixXd& basis,
                  const Eigen::MatrixXd& perp, int fitted_parameters, const fit::ResidualLayout& layout,
                  ScoreResult& out) {
  const fit::ResidualCorrelation c = fit::estimate_residual_correlation(r - explained, layout);
  if (!c.systematic) return;
  Eigen::MatrixXd span(r.size(), basis.cols() + perp.cols());
  span << basis, perp;
  const Eigen::MatrixXd span_basis = orthonormal_basis(span);
  const Eigen::VectorXd g = perp.transpose() * r;
  const Eigen::MatrixXd v = fit::span_share_correction(span_basis, layout, c) * fit::correlated_gram(perp, layout, c);
  const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(v);
  const int q = static_cast<int>(cod.rank());
  out.correlated = true;
  out.effective_residuals = c.effective_residuals;
  out.statistic = q > 0 ? g.dot(cod.solve(g)) : 0.0;
  const double dof = std::max(c.effective_residuals - fitted_parameters, 1.0);
  out.p_value = q > 0 && out.statistic > 0
                    ? boost::math::cdf(boost::math::complement(boost::math::fisher_f(q, dof), out.statistic / q))
                    : 1.0;
}

}  // namespace

ScoreResult score_test(const Eigen::VectorXd& r, const Eigen::MatrixXd& basis, int fitted_parameters,
                       const Eigen::MatrixXd& s, double in_span_tolerance, const fit::ResidualLayout* layout,
                       double data) {
  const Eigen::Index m = r.size();
  const double m_data = data > 0 ? data : static_cast<double>(m);
  if (basis.rows() != m || s.rows() != m)
    throw InvalidInput("score test: the residual (" + std::to_string(m) + "), the Jacobian (" +
                       std::to_string(basis.rows()) + ") and the candidate's sensitivity (" +
                       std::to_string(s.rows()) + ") must have the same rows");
  if (m_data <= fitted_parameters)
    throw InvalidInput("score test: " + std::to_string(static_cast<long>(m_data)) + " residuals cannot test beyond " +
                       std::to_string(fitted_parameters) + " fitted parameters");
  ScoreResult out;
  out.degrees_of_freedom = static_cast<int>(s.cols());
  out.step = Eigen::VectorXd::Zero(s.cols());
  Eigen::MatrixXd perp = s - basis * (basis.transpose() * s);
  double kept = 0, total = 0;
  for (Eigen::Index c = 0; c < s.cols(); ++c) {
    const double n = s.col(c).norm(), p = perp.col(c).norm();
    total += n * n;
    if (p <= in_span_tolerance * n || n == 0) perp.col(c).setZero();
    else kept += p * p;
  }
  out.projected_fraction = total > 0 ? std::sqrt(kept / total) : 0.0;
  const double s2 = r.squaredNorm() / (m_data - fitted_parameters);
  if (kept == 0 || !(s2 > 0)) return out;
  const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(perp);
  const Eigen::VectorXd coef = cod.solve(r);  // least-squares fit of r by S_perp
  const Eigen::VectorXd explained = perp * coef;
  out.statistic = explained.squaredNorm() / s2;
  out.p_value = chi2_tail(out.statistic, out.degrees_of_freedom);
  out.step = -coef;
  if (layout) robust_score(r, explained, basis, perp, fitted_parameters, *layout, out);
  return out;
}

}  // namespace finverse::loop
