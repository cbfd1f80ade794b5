// Bounded Levenberg-Marquardt polish (levenberg_marquardt.hpp).
#include "fit/levenberg_marquardt.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "fit/errors.hpp"
#include "fit/population_evaluation.hpp"

namespace finverse::fit {

Eigen::MatrixXd finite_difference_jacobian(const ParameterSpace& space, const ResidualFunction& function,
                                           const Eigen::VectorXd& z, const Eigen::VectorXd& r0,
                                           double fd_step, bool central, int threads,
                                           long* evaluations) {
  const int n = space.size();
  const Eigen::VectorXd lo = space.scaled_lower(), hi = space.scaled_upper();
  std::vector<Eigen::VectorXd> points;
  std::vector<double> steps(n);
  std::vector<int> two_sided(n, 0);
  for (int j = 0; j < n; ++j) {
    const double h = fd_step * (hi(j) - lo(j));
    if (central && z(j) - h >= lo(j) && z(j) + h <= hi(j)) {
      two_sided[j] = 1;
      steps[j] = h;
      Eigen::VectorXd a = z, b = z;
      a(j) += h;
      b(j) -= h;
      points.push_back(a);
      points.push_back(b);
    } else {
      // One-sided, pointing into the box. The actual difference of the rounded coordinates is
      // the step, so that h is exact.
      Eigen::VectorXd a = z;
      a(j) = z(j) + h <= hi(j) ? z(j) + h : z(j) - h;
      steps[j] = a(j) - z(j);
      points.push_back(a);
    }
  }
  const BatchEvaluation b = evaluate_batch(space, function, points, threads, true);
  if (evaluations) *evaluations += static_cast<long>(points.size());
  Eigen::MatrixXd jac = Eigen::MatrixXd::Zero(r0.size(), n);
  std::size_t k = 0;
  for (int j = 0; j < n; ++j) {
    if (two_sided[j]) {
      const Eigen::VectorXd& ra = b.residuals[k];
      const Eigen::VectorXd& rb = b.residuals[k + 1];
      if (ra.size() == r0.size() && rb.size() == r0.size()) jac.col(j) = (ra - rb) / (2 * steps[j]);
      k += 2;
    } else {
      const Eigen::VectorXd& ra = b.residuals[k];
      if (ra.size() == r0.size()) jac.col(j) = (ra - r0) / steps[j];
      k += 1;
    }
  }
  return jac;
}

LmResult levenberg_marquardt(const ParameterSpace& space, const ResidualFunction& function,
                             const Eigen::VectorXd& z0, const LmOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const int n = space.size();
  if (z0.size() != n) throw InvalidInput("polish: start vector has the wrong size");
  const Eigen::VectorXd lo = space.scaled_lower(), hi = space.scaled_upper();
  const int jacobian_cost = options.central ? 2 * n : n;
  const long cap = options.max_evaluations > 0 ? options.max_evaluations : 6L * (n + 1);
  if (cap < jacobian_cost + 1)
    throw InvalidInput("polish: max_evaluations " + std::to_string(cap) +
                       " cannot pay for one Jacobian (" + std::to_string(jacobian_cost + 1) + ")");

  LmResult out;
  out.z = z0.cwiseMax(lo).cwiseMin(hi);
  // Single evaluations run on the calling thread, so the FEM inside may use every core.
  auto evaluate = [&](const Eigen::VectorXd& z, Eigen::VectorXd& r, double& objective) {
    const BatchEvaluation b = evaluate_batch(space, function, {z}, 1, true);
    ++out.evaluations;
    r = b.residuals[0];
    objective = b.objective[0];
    return b.failures == 0;
  };
  auto finish = [&](const std::string& reason) {
    out.stop_reason = reason;
    out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
  };

  if (!evaluate(out.z, out.residuals, out.objective)) {
    out.sum_of_squares = std::numeric_limits<double>::infinity();
    return finish("the model failed at the start point");
  }
  out.sum_of_squares = out.residuals.squaredNorm();
  bool jacobian_current = false;
  double lambda = options.initial_damping;
  std::string reason;

  while (reason.empty()) {
    if (out.sum_of_squares == 0) {
      reason = "zero residual";
      break;
    }
    if (!jacobian_current) {
      if (out.iterations > 0 && options.moved) options.moved(out.z);
      out.jacobian = finite_difference_jacobian(space, function, out.z, out.residuals, options.fd_step,
                                                options.central, options.threads, &out.evaluations);
      jacobian_current = true;
    }
    const Eigen::MatrixXd& jac = out.jacobian;
    const Eigen::VectorXd g = jac.transpose() * out.residuals;
    const Eigen::MatrixXd a = jac.transpose() * jac;
    // Free variables: a bound the gradient pushes against holds its variable (projected LM).
    std::vector<int> free;
    for (int j = 0; j < n; ++j) {
      const bool held = (out.z(j) <= lo(j) && g(j) > 0) || (out.z(j) >= hi(j) && g(j) < 0);
      if (!held) free.push_back(j);
    }
    if (free.empty()) {
      reason = "every variable held at a bound";
      break;
    }
    const int nf = static_cast<int>(free.size());
    Eigen::MatrixXd af(nf, nf);
    Eigen::VectorXd gf(nf);
    for (int p = 0; p < nf; ++p) {
      gf(p) = g(free[p]);
      for (int q = 0; q < nf; ++q) af(p, q) = a(free[p], free[q]);
    }
    const double diag_max = af.diagonal().maxCoeff();
    if (!(diag_max > 0)) {
      reason = "the residuals do not depend on the free variables";
      break;
    }
    // Inner loop: raise the damping until a step lowers S.
    while (true) {
      if (out.evaluations + 1 + jacobian_cost > cap) {
        reason = "evaluation cap";
        break;
      }
      Eigen::MatrixXd m = af;
      for (int p = 0; p < nf; ++p) m(p, p) += lambda * std::max(af(p, p), 1e-12 * diag_max);
      const Eigen::VectorXd df = m.ldlt().solve(-gf);
      Eigen::VectorXd trial = out.z;
      for (int p = 0; p < nf; ++p) trial(free[p]) += df(p);
      trial = trial.cwiseMax(lo).cwiseMin(hi);
      if ((trial - out.z).lpNorm<Eigen::Infinity>() < options.step_tolerance) {
        reason = "step below tolerance";
        break;
      }
      Eigen::VectorXd r;
      double objective = 0;
      const bool ok = evaluate(trial, r, objective);
      const double s = ok ? r.squaredNorm() : std::numeric_limits<double>::infinity();
      if (options.progress) {
        std::ostringstream line;
        line << "LM step: |r|^2 " << out.sum_of_squares << " -> " << s
             << (s < out.sum_of_squares ? " taken" : " rejected") << ", damping " << lambda << ", " << out.evaluations
             << " of " << cap << " evaluations";
        options.progress(line.str());
      }
      if (s < out.sum_of_squares) {
        const double reduction = (out.sum_of_squares - s) / out.sum_of_squares;
        out.z = trial;
        out.residuals = std::move(r);
        out.objective = objective;
        out.sum_of_squares = s;
        ++out.iterations;
        jacobian_current = false;
        lambda = std::max(lambda / 3, 1e-12);
        if (reduction < options.reduction_tolerance) reason = "reduction below tolerance";
        break;
      }
      lambda *= 4;
      if (lambda > 1e12) {
        reason = "no decrease at any damping";
        break;
      }
    }
  }
  // The uncertainty needs the Jacobian at the returned point; the cap reserved its cost.
  if (!jacobian_current) {
    if (out.iterations > 0 && options.moved) options.moved(out.z);
    out.jacobian = finite_difference_jacobian(space, function, out.z, out.residuals, options.fd_step,
                                              options.central, options.threads, &out.evaluations);
  }
  return finish(reason);
}

}  // namespace finverse::fit
