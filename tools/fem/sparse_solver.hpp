// Sparse symmetric direct solver with symbolic-factorisation reuse: the ordering and symbolic
// analysis are done once per pattern (Assembler's upper triangle), the numeric factorisation per
// Newton iteration. Backends: cholmod (supernodal LL^T; on an indefinite tangent it falls back to
// simplicial LDL^T), simplicial_ldlt, and for the full non-symmetric tangent sparse_lu / umfpack
// (timings: docs/studies/fem_sparse_solver.md).
// Singularity: the symmetric paths factor the equilibrated S A S (s_i = |a_ii|^-1/2), so the pivot
// ratio tested against 1e-13 measures singularity, not the mix of rotation and translation units;
// SingularMatrix names the equation.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace finverse::fem {

enum class SolverBackend { cholmod, simplicial_ldlt, sparse_lu, umfpack };

SolverBackend parse_solver_backend(const std::string& name);  // throws InvalidInput
const char* to_string(SolverBackend backend);

class SparseSolver {
 public:
  using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

  explicit SparseSolver(SolverBackend backend = SolverBackend::cholmod);
  ~SparseSolver();
  SparseSolver(const SparseSolver&) = delete;
  SparseSolver& operator=(const SparseSolver&) = delete;

  // Factorises the symmetric matrix whose upper triangle is given (sparse_lu, umfpack: the full
  // matrix). `what` names the matrix in error messages ("tangent stiffness", "effective
  // stiffness", ...); describe(eq) names an equation ("node 3 rz").
  void factorize(const SparseMatrix& upper, const std::string& what = "stiffness matrix");
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;

  void set_equation_names(std::function<std::string(int)> describe) {
    describe_ = std::move(describe);
  }
  SolverBackend backend() const { return backend_; }
  int symbolic_count() const { return symbolic_count_; }
  int numeric_count() const { return numeric_count_; }
  bool used_fallback() const { return use_ldlt_now_; }

 private:
  struct Impl;
  bool same_pattern(const SparseMatrix& A) const;
  [[noreturn]] void singular(const std::string& what, int equation, double ratio) const;

  SolverBackend backend_;
  std::unique_ptr<Impl> impl_;
  std::vector<int> outer_, inner_;
  int symbolic_count_ = 0, numeric_count_ = 0;
  bool use_ldlt_now_ = false;
  std::function<std::string(int)> describe_;
};

}  // namespace finverse::fem
