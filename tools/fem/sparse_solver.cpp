// Sparse direct solver wrapper (see sparse_solver.hpp).
#include "fem/sparse_solver.hpp"

#include <omp.h>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <Eigen/UmfPackSupport>
#include <cmath>
#include <sstream>

#include "fem/errors.hpp"

namespace finverse::fem {

namespace {
// Gives access to CHOLMOD's reciprocal condition estimate, which Eigen does not expose.
// Same set-up as Eigen::CholmodSupernodalLLT.
class CholmodLLT : public Eigen::CholmodBase<SparseSolver::SparseMatrix, Eigen::Upper, CholmodLLT> {
  using Base = Eigen::CholmodBase<SparseSolver::SparseMatrix, Eigen::Upper, CholmodLLT>;

 public:
  CholmodLLT() {
    m_cholmod.final_asis = 1;
    m_cholmod.supernodal = CHOLMOD_SUPERNODAL;
    // Silent: an indefinite tangent (past a limit point) is an expected outcome that factorize()
    // reports through info() and the caller answers with LDL^T; every other failure also comes
    // back through info() and is thrown with a message. CHOLMOD must not write to stdout.
    m_cholmod.print = 0;
  }
  double rcond() const { return cholmod_rcond(m_cholmodFactor, &m_cholmod); }
};
constexpr double kSingularPivotRatio = 1e-13;

// Keeps every OpenMP region opened on this thread inactive (one thread) while it lives. Debian's
// CHOLMOD 3.0 opens teams of a fixed four threads (CHOLMOD_OMP_NUM_THREADS) around small loops of
// the supernodal factorisation, whatever --threads says; on the fin's tangent (7.3k DOFs) their
// fork and join cost as much as the factorisation itself (docs/studies/fit_evaluation_speed.md,
// "Sessions 38-39"). max-active-levels is an ICV of the calling thread's data environment, so
// lowering it to the current level touches no other thread and opens no team of its own.
class NoNewTeams {
 public:
  NoNewTeams() : levels_(omp_get_max_active_levels()) { omp_set_max_active_levels(omp_get_active_level()); }
  ~NoNewTeams() { omp_set_max_active_levels(levels_); }
  NoNewTeams(const NoNewTeams&) = delete;
  NoNewTeams& operator=(const NoNewTeams&) = delete;

 private:
  int levels_;
};

// Numeric factorisation of A with the symbolic analysis done once per pattern (the reuse across
// Newton iterations and runs); true when the factorisation succeeded.
template <class Solver>
bool factor(Solver& solver, bool& analysed, int& symbolic_count, const SparseSolver::SparseMatrix& A) {
  if (!analysed) {
    solver.analyzePattern(A);
    analysed = true;
    ++symbolic_count;
  }
  {
    const NoNewTeams serial;
    solver.factorize(A);
  }
  return solver.info() == Eigen::Success;
}
}  // namespace

struct SparseSolver::Impl {
  // Symmetric diagonal scaling B = S A S, s_i = |a_ii|^(-1/2): the Cholesky/LDL^T paths factor B,
  // whose unit diagonal makes the pivot ratio a test of singularity and not of units. A fin mixes
  // rotations of a 50 um membrane (D ~ 1e-7 N m) with translations of 0.4 mm rays (EA/L ~ 1e6
  // N/m), a pivot ratio of 1e-13 in SI units for a perfectly regular structure.
  SparseSolver::SparseMatrix scaled;
  Eigen::VectorXd scale;
  CholmodLLT cholmod;
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Upper> ldlt;
  Eigen::SparseLU<SparseMatrix, Eigen::COLAMDOrdering<int>> lu;
  Eigen::UmfPackLU<SparseMatrix> umfpack;
  bool cholmod_analysed = false, ldlt_analysed = false, lu_analysed = false;
};

SolverBackend parse_solver_backend(const std::string& name) {
  if (name == "cholmod") return SolverBackend::cholmod;
  if (name == "simplicial_ldlt") return SolverBackend::simplicial_ldlt;
  throw InvalidInput("solver backend '" + name + "', expected cholmod or simplicial_ldlt");
}

const char* to_string(SolverBackend b) {
  switch (b) {
    case SolverBackend::cholmod: return "cholmod";
    case SolverBackend::simplicial_ldlt: return "simplicial_ldlt";
    case SolverBackend::sparse_lu: return "sparse_lu";
    case SolverBackend::umfpack: return "umfpack";
  }
  return "?";
}

SparseSolver::SparseSolver(SolverBackend backend)
    : backend_(backend), impl_(std::make_unique<Impl>()) {}
SparseSolver::~SparseSolver() = default;

bool SparseSolver::same_pattern(const SparseMatrix& A) const {
  if (static_cast<int>(outer_.size()) != A.outerSize() + 1) return false;
  if (static_cast<Eigen::Index>(inner_.size()) != A.nonZeros()) return false;
  return std::equal(outer_.begin(), outer_.end(), A.outerIndexPtr()) &&
         std::equal(inner_.begin(), inner_.end(), A.innerIndexPtr());
}

void SparseSolver::singular(const std::string& what, int equation, double ratio) const {
  std::ostringstream os;
  os.precision(3);
  os << what << " is singular (pivot ratio " << ratio << "): the structure has an unconstrained"
     << " rigid-body mode or mechanism";
  if (equation >= 0) os << ", first at " << (describe_ ? describe_(equation) : "equation " + std::to_string(equation));
  os << "; check the prescribed DOFs";
  throw SingularMatrix(os.str());
}

void SparseSolver::factorize(const SparseMatrix& A, const std::string& what) {
  if (!A.isCompressed()) throw InvalidInput("SparseSolver: matrix must be compressed");
  const bool new_pattern = !same_pattern(A);
  if (new_pattern) {
    outer_.assign(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1);
    inner_.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
    impl_->cholmod_analysed = impl_->ldlt_analysed = impl_->lu_analysed = false;
  }
  for (Eigen::Index k = 0; k < A.nonZeros(); ++k)
    if (!std::isfinite(A.valuePtr()[k]))
      throw NotConverged(what + " contains NaN/Inf entries (the solution diverged)");
  ++numeric_count_;
  if (backend_ == SolverBackend::sparse_lu) {
    if (!factor(impl_->lu, impl_->lu_analysed, symbolic_count_, A)) singular(what, -1, 0.0);
    return;
  }
  if (backend_ == SolverBackend::umfpack) {
    if (!factor(impl_->umfpack, impl_->lu_analysed, symbolic_count_, A)) singular(what, -1, 0.0);
    return;
  }
  use_ldlt_now_ = backend_ == SolverBackend::simplicial_ldlt;
  // Equilibrate (see Impl): same pattern, values scaled by s_i s_j.
  auto& S = impl_->scale;
  S.setOnes(A.rows());
  for (int j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      if (it.row() == j && it.value() != 0) S(j) = 1.0 / std::sqrt(std::abs(it.value()));
  impl_->scaled = A;
  for (int j = 0; j < impl_->scaled.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(impl_->scaled, j); it; ++it) it.valueRef() *= S(it.row()) * S(j);
  const SparseMatrix& B = impl_->scaled;
  if (!use_ldlt_now_) {
    if (factor(impl_->cholmod, impl_->cholmod_analysed, symbolic_count_, B)) {
      const double rc = impl_->cholmod.rcond();
      if (!(rc > kSingularPivotRatio)) singular(what, -1, rc);
      return;
    }
    use_ldlt_now_ = true;  // not positive definite: indefinite tangent or singular
  }
  auto& ldlt = impl_->ldlt;
  factor(ldlt, impl_->ldlt_analysed, symbolic_count_, B);
  const Eigen::VectorXd D = ldlt.vectorD();
  const double dmax = D.cwiseAbs().maxCoeff();
  Eigen::Index worst = 0;
  const double dmin = D.cwiseAbs().minCoeff(&worst);
  const double ratio = dmax > 0 ? dmin / dmax : 0.0;
  if (ldlt.info() != Eigen::Success || !(ratio > kSingularPivotRatio))
    singular(what, ldlt.permutationPinv().indices()(worst), ratio);
}

Eigen::VectorXd SparseSolver::solve(const Eigen::VectorXd& b) const {
  if (backend_ == SolverBackend::sparse_lu) return impl_->lu.solve(b);
  if (backend_ == SolverBackend::umfpack) return impl_->umfpack.solve(b);
  const Eigen::VectorXd& S = impl_->scale;
  const Eigen::VectorXd y = S.cwiseProduct(b);
  if (use_ldlt_now_) return S.cwiseProduct(impl_->ldlt.solve(y));
  return S.cwiseProduct(impl_->cholmod.solve(y));
}

}  // namespace finverse::fem
