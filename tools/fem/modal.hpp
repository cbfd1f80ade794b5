// Natural frequencies and modes of the structure linearised about a configuration:
//   K_T phi = omega^2 M phi   on the free DOFs (K_T: symmetrised tangent, M: consistent mass).
// Small systems (<= dense_limit free DOFs) use a dense generalized self-adjoint eigensolver
// (Eigen, LAPACK-free); larger ones use subspace iteration (Bathe & Wilson 1972; Bathe, "Finite
// Element Procedures", sec. 11.6) with the sparse factorisation of K_T and q = min(2p, p + 8)
// iteration vectors, converged when the p wanted eigenvalues change by < tolerance.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "fem/model.hpp"
#include "fem/sparse_solver.hpp"

namespace finverse::fem {

struct ModalOptions {
  int modes = 6;
  int dense_limit = 2000;
  double tolerance = 1e-10;
  int max_iterations = 200;
  SolverBackend backend = SolverBackend::cholmod;
  bool force_subspace = false;  // for testing the iterative path on small models
};

struct ModalResult {
  Eigen::VectorXd omega;      // rad/s, ascending
  Eigen::VectorXd frequency;  // Hz
  Eigen::MatrixXd shapes;     // full-length (6 per node) mass-normalised modes, one per column
  int iterations = 0;         // subspace iterations (0 for dense)
};

ModalResult modal_analysis(const Model& model, const NodalState& state, const ModalOptions& options);

}  // namespace finverse::fem
