// Gauss-Newton covariance, intervals and identifiability verdicts (uncertainty.hpp).
#include "fit/uncertainty.hpp"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <limits>

#include "fit/correlated_residual.hpp"
#include "fit/errors.hpp"

namespace finverse::fit {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// (J^T J)^+ over the directions the SVD does not count singular, and each parameter's squared
// share of the null space (1: J cannot see it at all).
struct Inverse {
  Eigen::MatrixXd pinv;
  Eigen::VectorXd null_share;
};

Inverse gram_inverse(const Eigen::MatrixXd& jacobian, const UncertaintyOptions& options, Uncertainty& u) {
  const auto n = jacobian.cols();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(jacobian, Eigen::ComputeThinV);
  const Eigen::MatrixXd& v = svd.matrixV();
  const int k = static_cast<int>(svd.singularValues().size());  // min(m, n)
  // n values, descending; with m < n the directions J cannot see have singular value zero.
  u.singular_values = Eigen::VectorXd::Zero(n);
  u.singular_values.head(k) = svd.singularValues();
  const double smax = k > 0 ? u.singular_values(0) : 0.0;
  Inverse out{Eigen::MatrixXd::Zero(n, n), Eigen::VectorXd::Ones(n)};
  for (int i = 0; i < k; ++i) {
    const double sigma = u.singular_values(i);
    if (!(sigma > options.singular_tolerance * smax) || sigma == 0) continue;
    out.pinv += v.col(i) * v.col(i).transpose() / (sigma * sigma);
    out.null_share -= v.col(i).cwiseAbs2();
  }
  return out;
}

double t_quantile(double degrees_of_freedom, double confidence) {
  if (!(degrees_of_freedom > 0)) return inf;
  boost::math::students_t dist(degrees_of_freedom);
  return boost::math::quantile(boost::math::complement(dist, (1 - confidence) / 2));
}

std::string verdict_of(const ParameterSpace& space, int j, const Eigen::VectorXd& z, double half, bool singular,
                       bool insensitive, int degrees_of_freedom, const UncertaintyOptions& options) {
  const Eigen::VectorXd lo = space.scaled_lower(), hi = space.scaled_upper();
  const double range = hi(j) - lo(j);
  const bool at_bound =
      z(j) - lo(j) <= options.bound_tolerance * range || hi(j) - z(j) <= options.bound_tolerance * range;
  const bool log_scale = space[j].scale == Scale::log10;
  if (degrees_of_freedom <= 0) return "no residual degrees of freedom";
  if (singular) return "insensitive: near-singular Jacobian direction";
  if (at_bound) return "at bound";
  if (log_scale && 2 * half > 1) return "interval spans more than a decade";
  if (!log_scale && 2 * half > space[j].upper - space[j].lower) return "interval wider than the bounds";
  // A bound inside the interval limits the parameter, not the data; the normal interval does not
  // hold at a boundary (Self & Liang 1987), so it is not called identified.
  if (z(j) - half <= lo(j) || z(j) + half >= hi(j)) return "interval reaches a bound";
  if (insensitive) return "insensitive: across its bounds it moves the residual less than the model misfit left";
  return "identified";
}

}  // namespace

Uncertainty compute_uncertainty(const ParameterSpace& space, const Eigen::VectorXd& z, const Eigen::VectorXd& r,
                                const Eigen::MatrixXd& jacobian, const UncertaintyOptions& options,
                                const ResidualLayout* layout) {
  const int n = space.size();
  const Eigen::Index m = r.size();
  if (z.size() != n || jacobian.cols() != n || jacobian.rows() != m)
    throw InvalidInput("uncertainty: Jacobian is " + std::to_string(jacobian.rows()) + " x " +
                       std::to_string(jacobian.cols()) + ", expected " + std::to_string(m) + " x " + std::to_string(n));
  Uncertainty u;
  u.degrees_of_freedom = static_cast<int>(m - n);
  u.residual_variance =
      u.degrees_of_freedom > 0 ? r.squaredNorm() / u.degrees_of_freedom : std::numeric_limits<double>::quiet_NaN();
  const Inverse inv = gram_inverse(jacobian, options, u);

  u.correlation = Eigen::MatrixXd::Identity(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      if (i != j) {
        const double d = inv.pinv(i, i) * inv.pinv(j, j);
        u.correlation(i, j) = d > 0 ? inv.pinv(i, j) / std::sqrt(d) : 0.0;
      }

  // Independent residuals: s^2 (J^T J)^+. A systematic (correlated) misfit: the sandwich with
  // its correlation over the fin, samples and components, and the effective number of residuals
  // for the quantile (at least one degree of freedom: fewer than n makes the intervals wide).
  Eigen::VectorXd variance = u.residual_variance * inv.pinv.diagonal();
  double dof = u.degrees_of_freedom;
  if (layout) {
    const ResidualCorrelation c = estimate_residual_correlation(r, *layout, options.systematic_correlation);
    u.systematic_misfit = c.systematic;
    u.misfit_correlation_length = c.length;
    u.misfit_neighbour_correlation = c.neighbour;
    u.effective_residuals = c.effective_residuals;
    u.effective_channels = c.effective_channels;
    if (c.systematic && c.length > 0) {
      // K from r lacks the misfit's part in span(J) (span_share_correction).
      const Eigen::MatrixXd q = Eigen::HouseholderQR<Eigen::MatrixXd>(jacobian).householderQ() *
                                Eigen::MatrixXd::Identity(m, std::min<Eigen::Index>(m, n));
      const double scale = span_share_correction(q, *layout, c);
      const Eigen::MatrixXd sandwich = scale * (inv.pinv * correlated_gram(jacobian, *layout, c) * inv.pinv);
      variance = variance.cwiseMax(sandwich.diagonal());
      dof = std::max(c.effective_residuals - n, 1.0);
    }
  }
  const double t = t_quantile(dof, options.confidence);

  u.standard_error.resize(n);
  u.lower95.resize(n);
  u.upper95.resize(n);
  u.identified.assign(n, 0);
  u.verdict.assign(n, "");
  const double misfit = r.norm();
  const Eigen::VectorXd lo = space.scaled_lower(), hi = space.scaled_upper();
  for (int j = 0; j < n; ++j) {
    const bool singular = inv.null_share(j) > options.singular_share;
    const double se = (u.degrees_of_freedom > 0 && !singular) ? std::sqrt(variance(j)) : inf;
    u.standard_error(j) = se;
    const double half = t * se;
    u.lower95(j) = space.to_physical(j, z(j) - half);
    u.upper95(j) = space.to_physical(j, z(j) + half);
    // Linearised: the residual change of moving the parameter across its whole range. Against a
    // systematic misfit only: independent noise averages down over many residuals, a model's
    // misfit does not, and a parameter that cannot move the prediction by as much is not seen.
    const bool insensitive = u.systematic_misfit && jacobian.col(j).norm() * (hi(j) - lo(j)) < misfit;
    std::string v = verdict_of(space, j, z, half, singular, insensitive, u.degrees_of_freedom, options);
    u.identified[j] = v == "identified" ? 1 : 0;
    u.verdict[j] = u.systematic_misfit ? "model misfit dominates: " + v : v;
  }
  return u;
}

}  // namespace finverse::fit
