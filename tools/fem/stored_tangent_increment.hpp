// Eq. (2)'s converged increment, solved from a reference solution on its stored tangent (issue 45,
// goal 8). Newton from the flat, stress-free base overshoots and spends about ten factorisations
// per increment on the fin. Here the increment is solved once at reference moduli; its converged
// state x_ref and the tangent there (a TangentBasis: linear in the element moduli at a fixed
// configuration) are kept. An evaluation at other moduli starts from x_ref, factorises
// K(x_ref; E, nu) once and iterates u += K^-1 r(x) with Anderson mixing (the least-squares secant
// of fsi/iqn_ils.hpp), one force assembly and one back-substitution per iteration, a true tangent
// when it stalls. It stops on StaticSolver's test, so its answer is Newton's equilibrium; solve()
// returns false where it does not converge and the caller uses Newton. Near the reference (a
// polish's Jacobian column) the reference's own tangent, factorised once per workspace, serves
// instead of a new factorisation; the answer depends on the moduli and the reference alone.
// Numbers: docs/studies/fit_evaluation_speed.md, "Sessions 38-39" and "Session 43".
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "fem/assembly.hpp"
#include "fem/model.hpp"
#include "fem/nodal_state.hpp"
#include "fem/sparse_solver.hpp"
#include "fem/tangent_basis.hpp"

namespace finverse::fem {

struct StoredTangentOptions {
  int max_iterations = 30;             // then solve() gives up (the caller's Newton takes over)
  int history = 6;                     // Anderson columns kept
  double residual_tolerance = 1e-8;    // as StaticOptions
  double increment_tolerance = 1e-10;  // as StaticOptions
  // When the residual falls by less than this factor in an iteration, the true tangent at the
  // iterate is assembled and factorised (a Newton step), at most max_refreshes times.
  double refresh_ratio = 0.9;
  int max_refreshes = 4;
  // Near the reference (every element modulus within this relative change of the reference's and
  // nu within reuse_nu) the iteration runs on the reference's tangent instead of factorising
  // K(x_ref; E, nu). 0 turns this off; it needs set_reference_moduli().
  double reuse_within = 0.05;
  double reuse_nu = 0.01;
};

struct StoredTangentInfo {
  int iterations = 0;
  int refreshes = 0;  // true tangents factorised (the reference's not counted)
  bool converged = false;
  bool reused_reference = false;  // ran on the reference's factorised tangent
  double residual = 0;            // relative, last
};

class StoredTangentIncrement {
 public:
  // models, nus: as TangentBasis (the first model outlives this object); reference: a converged
  // increment's state at t_next (the prescribed DOFs at their values at t_next), at the
  // reference moduli; t_next: the stiffness field's time.
  StoredTangentIncrement(const std::vector<const Model*>& models, const std::vector<double>& nus,
                         const NodalState& reference, double t_next, StoredTangentOptions options = {});

  // The moduli (per element) and nu at which the reference was solved: evaluations near them
  // reuse the reference's tangent (StoredTangentOptions::reuse_within).
  void set_reference_moduli(std::vector<double> element_moduli, double nu);

  // Per-thread state: the factorisation (its symbolic analysis is kept) and scratch, and the
  // reference tangents of the last few increments this workspace solved near their references.
  struct Workspace {
    explicit Workspace(SolverBackend backend = SolverBackend::cholmod) : solver(backend), backend(backend) {}
    SparseSolver solver;
    SolverBackend backend;
    Assembler::SparseMatrix matrix;
    TangentBasis::Scratch scratch;
    struct ReferenceFactor {
      std::uint64_t id = 0;  // the StoredTangentIncrement's
      std::unique_ptr<SparseSolver> solver;
      double floor = 0;  // roundoff_force_floor of the reference tangent
    };
    std::vector<ReferenceFactor> references;
  };

  // Solves f_int(x) = f_target on the free DOFs from the reference. assembler: of the model at the
  // evaluation's moduli (same topology as the basis's models), evaluated at `time` (t_next);
  // element_moduli, nu: that model's (Model::element_youngs_modulus at t_next; nu as TangentBasis
  // ::combine); f_target (full length): f_ext(t_next) minus QuasiStaticIncrement's base offset.
  // x: the converged state on true. False when the iteration stalls, diverges or runs out of
  // iterations (x is then unspecified). Throws SingularMatrix when K cannot be factorised.
  bool solve(Assembler& assembler, double time, const std::vector<double>& element_moduli, double nu,
             const Eigen::VectorXd& f_target, NodalState& x, Workspace& workspace,
             StoredTangentInfo* info = nullptr) const;

  const NodalState& reference() const { return reference_; }
  bool near_reference(const std::vector<double>& element_moduli, double nu) const;
  const TangentBasis& basis() const { return *basis_; }

 private:
  const Workspace::ReferenceFactor& reference_factor(Workspace& w) const;

  std::unique_ptr<TangentBasis> basis_;
  NodalState reference_;
  std::vector<double> reference_moduli_;
  double reference_nu_ = 0;
  std::uint64_t id_;
  StoredTangentOptions opt_;
  double lchar_ = 1;
};

}  // namespace finverse::fem
