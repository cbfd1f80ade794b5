// Eq. (2)'s increment linearised at its base (issue 45): the first Newton step of
// QuasiStaticIncrement, predictor for the prescribed motion and load increment in one solve,
//     K_ff du_f = [f_ext(t_next) - f_ext(t) + g]_f - [K dp]_f,
// K = K(E, nu) at the base from a TangentBasis, dp the prescribed increment, g a known load
// change. One weighted gather, one numeric factorisation (symbolic reused), one solve. Its error
// is second order in the increment; on the fin it is 4-5 % at the file's moduli because the
// membrane's response over a frame is nonlinear (docs/studies/fit_evaluation_speed.md). The moduli
// must be constant over [t, t_next], so that the base's internal force cancels against the offset.
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
