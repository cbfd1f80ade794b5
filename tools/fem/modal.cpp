// Linearised modal analysis (see modal.hpp).
#include "fem/modal.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Eigenvalues>

#include "fem/assembly.hpp"
#include "fem/dof_map.hpp"
#include "fem/errors.hpp"
#include "fem/static_solver.hpp"

namespace finverse::fem {

namespace {
// Generalized eigenproblem of small dense symmetric matrices, ascending.
void dense_eigen(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, Eigen::VectorXd& lambda,
                 Eigen::MatrixXd& phi) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
  if (es.info() != Eigen::Success)
    throw SingularMatrix("modal analysis: mass matrix is not positive definite (zero density?)");
  lambda = es.eigenvalues();
  phi = es.eigenvectors();
}
}  // namespace

ModalResult modal_analysis(const Model& model, const NodalState& state, const ModalOptions& opt) {
  model.validate();
  const DofMap dofs(model);
  Assembler assembler(model, dofs);
  const int n = dofs.free();
  const int p = std::min(opt.modes, n);
  if (p < 1) throw InvalidInput("modal analysis: no free DOFs or no modes requested");

  AssemblyRequest req;
  req.matrix = true;
  req.stiffness_coefficient = 0;
  req.mass_coefficient = 1;
  assembler.assemble(state, req);
  const Assembler::SparseMatrix M = assembler.matrix();
  req.stiffness_coefficient = 1;
  req.mass_coefficient = 0;
  assembler.assemble(state, req);
  const Assembler::SparseMatrix& K = assembler.matrix();

  Eigen::VectorXd lambda;
  Eigen::MatrixXd phi;
  ModalResult result;
  if (n <= opt.dense_limit && !opt.force_subspace) {
    const Assembler::SparseMatrix Kf = K.selfadjointView<Eigen::Upper>();
    const Assembler::SparseMatrix Mf = M.selfadjointView<Eigen::Upper>();
    const Eigen::MatrixXd Kd = Eigen::MatrixXd(Kf), Md = Eigen::MatrixXd(Mf);
    // A singular K means a rigid-body mode: report it the same way as the static solver.
    SparseSolver check(opt.backend);
    check.set_equation_names([&](int eq) { return describe_equation(dofs, eq); });
    check.factorize(K, "tangent stiffness");
    dense_eigen(Kd, Md, lambda, phi);
  } else {
    SparseSolver solver(opt.backend);
    solver.set_equation_names([&](int eq) { return describe_equation(dofs, eq); });
    solver.factorize(K, "tangent stiffness");
    const int q = std::min({2 * p, p + 8, n});
    // Starting vectors: the mass diagonal plus fixed-seed noise (deterministic).
    Eigen::MatrixXd X(n, q);
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    for (int j = 0; j < q; ++j)
      for (int i = 0; i < n; ++i) X(i, j) = (j == 0 ? M.coeff(i, i) : U(rng));
    Eigen::VectorXd previous = Eigen::VectorXd::Constant(q, INFINITY);
    for (int it = 1; it <= opt.max_iterations; ++it) {
      const Eigen::MatrixXd Y = M.selfadjointView<Eigen::Upper>() * X;
      Eigen::MatrixXd Xb(n, q);
      for (int j = 0; j < q; ++j) Xb.col(j) = solver.solve(Y.col(j));
      const Eigen::MatrixXd Kr = Xb.transpose() * Y;  // = Xb^T K Xb since K Xb = Y
      const Eigen::MatrixXd Mr = Xb.transpose() * (M.selfadjointView<Eigen::Upper>() * Xb);
      Eigen::VectorXd lr;
      Eigen::MatrixXd Q;
      dense_eigen(0.5 * (Kr + Kr.transpose()), 0.5 * (Mr + Mr.transpose()), lr, Q);
      X = Xb * Q;
      result.iterations = it;
      const double change =
          ((lr.head(p) - previous.head(p)).cwiseAbs().array() / lr.head(p).cwiseAbs().array())
              .maxCoeff();
      previous = lr;
      if (change < opt.tolerance) break;
      if (it == opt.max_iterations)
        throw NotConverged("modal analysis: subspace iteration did not converge in " +
                           std::to_string(it) + " iterations");
    }
    lambda = previous;
    phi = X;
  }
  result.omega.resize(p);
  result.frequency.resize(p);
  result.shapes = Eigen::MatrixXd::Zero(dofs.total(), p);
  for (int k = 0; k < p; ++k) {
    result.omega(k) = std::sqrt(std::max(lambda(k), 0.0));
    result.frequency(k) = result.omega(k) / (2 * std::numbers::pi);
    result.shapes.col(k) = dofs.scatter_free(phi.col(k));
  }
  return result;
}

}  // namespace finverse::fem
