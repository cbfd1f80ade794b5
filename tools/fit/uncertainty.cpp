// Gauss-Newton covariance, intervals and identifiability verdicts (uncertainty.hpp).
#include "fit/uncertainty.hpp"

#include <cmath>
#include <limits>

#include <Eigen/SVD>
#include <boost/math/distributions/students_t.hpp>

#include "fit/errors.hpp"

namespace finverse::fit {

Uncertainty compute_uncertainty(const ParameterSpace& space, const Eigen::VectorXd& z,
                                const Eigen::VectorXd& r, const Eigen::MatrixXd& jacobian,
                                const UncertaintyOptions& options) {
  const int n = space.size();
  const Eigen::Index m = r.size();
  if (z.size() != n || jacobian.cols() != n || jacobian.rows() != m)
    throw InvalidInput("uncertainty: Jacobian is " + std::to_string(jacobian.rows()) + " x " +
                       std::to_string(jacobian.cols()) + ", expected " + std::to_string(m) + " x " +
                       std::to_string(n));
  constexpr double inf = std::numeric_limits<double>::infinity();

  Uncertainty u;
  u.degrees_of_freedom = static_cast<int>(m - n);
  u.residual_variance = u.degrees_of_freedom > 0 ? r.squaredNorm() / u.degrees_of_freedom
                                                 : std::numeric_limits<double>::quiet_NaN();

  Eigen::JacobiSVD<Eigen::MatrixXd> svd(jacobian, Eigen::ComputeThinV);
  const Eigen::MatrixXd& v = svd.matrixV();
  const int k = static_cast<int>(svd.singularValues().size());  // min(m, n)
  // n values, descending; with m < n the directions J cannot see have singular value zero.
  u.singular_values = Eigen::VectorXd::Zero(n);
  u.singular_values.head(k) = svd.singularValues();
  const double smax = k > 0 ? u.singular_values(0) : 0.0;
  // (J^T J)^+ over the non-singular directions; the null space is V's other columns, plus the
  // directions J cannot see at all when m < n.
  Eigen::MatrixXd pinv = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd null_share = Eigen::VectorXd::Ones(n);
  for (int i = 0; i < k; ++i) {
    const double sigma = u.singular_values(i);
    if (!(sigma > options.singular_tolerance * smax) || sigma == 0) continue;
    pinv += v.col(i) * v.col(i).transpose() / (sigma * sigma);
    null_share -= v.col(i).cwiseAbs2();
  }

  u.correlation = Eigen::MatrixXd::Identity(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      if (i != j) {
        const double d = pinv(i, i) * pinv(j, j);
        u.correlation(i, j) = d > 0 ? pinv(i, j) / std::sqrt(d) : 0.0;
      }

  double t = inf;
  if (u.degrees_of_freedom > 0) {
    boost::math::students_t dist(u.degrees_of_freedom);
    t = boost::math::quantile(boost::math::complement(dist, (1 - options.confidence) / 2));
  }

  const Eigen::VectorXd lo = space.scaled_lower(), hi = space.scaled_upper();
  u.standard_error.resize(n);
  u.lower95.resize(n);
  u.upper95.resize(n);
  u.identified.assign(n, 0);
  u.verdict.assign(n, "");
  for (int j = 0; j < n; ++j) {
    const bool singular = null_share(j) > options.singular_share;
    const double se = (u.degrees_of_freedom > 0 && !singular)
                          ? std::sqrt(u.residual_variance * pinv(j, j))
                          : inf;
    u.standard_error(j) = se;
    const double half = t * se;
    u.lower95(j) = space.to_physical(j, z(j) - half);
    u.upper95(j) = space.to_physical(j, z(j) + half);
    const double range = hi(j) - lo(j);
    const bool at_bound = z(j) - lo(j) <= options.bound_tolerance * range ||
                          hi(j) - z(j) <= options.bound_tolerance * range;
    const bool log_scale = space[j].scale == Scale::log10;
    if (u.degrees_of_freedom <= 0)
      u.verdict[j] = "no residual degrees of freedom";
    else if (singular)
      u.verdict[j] = "insensitive: near-singular Jacobian direction";
    else if (at_bound)
      u.verdict[j] = "at bound";
    else if (log_scale && 2 * half > 1)
      u.verdict[j] = "interval spans more than a decade";
    else if (!log_scale && 2 * half > space[j].upper - space[j].lower)
      u.verdict[j] = "interval wider than the bounds";
    else {
      u.verdict[j] = "identified";
      u.identified[j] = 1;
    }
  }
  return u;
}

}  // namespace finverse::fit
