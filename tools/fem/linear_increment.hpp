// Eq. (2)'s increment linearised at its base (issue 45, deliverable 5): the first Newton step of
// QuasiStaticIncrement, its consistent predictor for the prescribed motion and the load increment
// in one solve,
//     K_ff du_f = [f_ext(t_next) - f_ext(t) + g]_f - [K dp]_f,
// with K = K(E, nu) the tangent at the base (tangent_basis.hpp), dp the prescribed DOFs' increment
// and g a known load change (the inertial -M da of eq. (2) with inertia). Per evaluation: one
// weighted gather of stored element matrices, one numeric factorisation with the pattern's
// symbolic analysis reused, one solve; no element is evaluated. Against the converged Newton
// increment it errs to second order in the increment (the root's rotation over one frame);
// measured in docs/studies/fit_evaluation_speed.md.
//
// The moduli must be constant over [t, t_next] (no modulation): the base's internal force then
// cancels against the offset that takes the base as in equilibrium, as in QuasiStaticIncrement.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "fem/model.hpp"
#include "fem/nodal_state.hpp"
#include "fem/sparse_solver.hpp"
#include "fem/tangent_basis.hpp"

namespace finverse::fem {

class LinearIncrement {
 public:
  // models, nus: as TangentBasis (the first model outlives this object); base: the state at t
  // with the prescribed DOFs at their values at t; load_change (full length, optional): as
  // QuasiStaticIncrement::solve.
  LinearIncrement(const std::vector<const Model*>& models, const std::vector<double>& nus, const NodalState& base,
                  double t, double t_next, const Eigen::VectorXd* load_change = nullptr);

  // Per-thread state: the factorisation (its symbolic analysis is kept) and scratch.
  struct Workspace {
    explicit Workspace(SolverBackend backend = SolverBackend::cholmod) : solver(backend) {}
    SparseSolver solver;
    Assembler::SparseMatrix matrix;
    TangentBasis::Scratch scratch;
    Eigen::VectorXd kv;
  };

  // dx per node [node][xyz] for element moduli E_e (Model::element_youngs_modulus) and Poisson
  // ratio nu: the free DOFs' solution, the prescribed translations' increment, zero where fixed.
  // Throws SingularMatrix (naming the equation) when K_ff cannot be factorised.
  std::vector<Vec3> displacement_increment(const std::vector<double>& element_moduli, double nu,
                                           Workspace& workspace) const;

  const TangentBasis& basis() const { return *basis_; }

 private:
  std::unique_ptr<TangentBasis> basis_;
  Eigen::VectorXd dp_;         // full length
  Eigen::VectorXd load_free_;  // [f_ext(t_next) - f_ext(t) + g]_f
};

}  // namespace finverse::fem
