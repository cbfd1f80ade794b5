// The quantity every optimiser of the fit minimises (the seed paper's eqs. (1) and (2)):
// residuals r(p) = sqrt(w_i) (dx_FE^i - dx_target^i), three components per node and sample, in
// metres, for the physical parameter vector p. From them:
//   distance objective  J = sum_k sqrt(w_k) |r_k| / sum_k w_k  over node-samples k (r_k the
//                       node-sample's 3-vector): the paper's sum of point-to-point distances, as
//                       a weighted mean distance [m]; the GA and CMA-ES minimise it.
//   least squares       S = |r|^2: the Levenberg-Marquardt polish and the covariance use it.
// With node weights w_i (non-uniform meshes: the node's share of the area), both reduce to the
// paper's unweighted forms on a uniform mesh.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "fit/residual_layout.hpp"

namespace finverse::fit {

class ResidualFunction {
 public:
  virtual ~ResidualFunction() = default;
  virtual int parameter_count() const = 0;
  virtual int residual_count() const = 0;  // 3 x node-samples
  // Thread-safe: called concurrently from several threads, each evaluation self-contained (it
  // builds or copies what it mutates). Throws fem::NotConverged / fem::SingularMatrix when the
  // model fails for these parameters: the optimisers give such a point the worst objective.
  virtual Eigen::VectorXd residuals(const Eigen::VectorXd& physical) const = 0;
  // sqrt(w) per node-sample (length residual_count() / 3), for the distance objective.
  virtual const Eigen::VectorXd& sqrt_weights() const = 0;
  // The samples' times (eq. (2) instants, eq. (1) frames, static load levels) when the residuals
  // are sample-major in equal blocks, one per time; empty: one block (`fin-fit evaluate` prints
  // the misfit per block).
  virtual std::vector<double> block_times() const { return {}; }
  // Where each residual sits, for the intervals' correlated-misfit estimate (residual_layout.hpp);
  // none: the residuals are taken as independent.
  virtual std::optional<ResidualLayout> residual_layout() const { return std::nullopt; }
  // A hint that the next evaluations lie near `physical` (a polish about to start): a function
  // that solves iteratively may start from a solution there. Its results may change within its
  // solver's tolerance, never more. Not called while evaluations run. Default: nothing.
  virtual void expect_near(const Eigen::VectorXd& /*physical*/) const {}
};

// The distance objective J of the residuals r (see above); sqrt_weights as sqrt_weights().
double mean_distance(const Eigen::VectorXd& r, const Eigen::VectorXd& sqrt_weights);

}  // namespace finverse::fit
