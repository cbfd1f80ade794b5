// The paper's quasi-static increment (Liu et al., section 2.2, objective eq. (2)): the fin's
// inertia is dropped, the deformed state at t is the base and taken to be in equilibrium, and
// the displacement increment dx over [t, t + dt] is the static response to the load increment
// f_ext(t + dt) - f_ext(t) plus the increment of the prescribed root motion.
//
// "Taken to be in equilibrium" is implemented by measuring internal forces from the base:
//     f_int(x) - f_int(x_t; E(t)) = f_ext(t + dt) - f_ext(t),   x = x_t on entry,
// i.e. a static Newton solve whose balance is offset by the base's out-of-balance force
// f_int(x_t) - f_ext(t). When the base is a converged equilibrium (marching with our own states)
// the offset is zero up to the tolerance and a chain of increments reproduces the full nonlinear
// static path; when the base is a reconstructed shape (the inverse fit), the same call applies
// the paper's assumption without requiring the reconstruction to balance the CFD loads.
// Stiffness and moduli are those of the model at t + dt (stiffness_field.hpp), so a fitter
// changes E with Model::set_*_youngs_modulus between calls.
//
// Meant to be called thousands of times in one process: the DofMap, assembler and the sparse
// solver (with its symbolic factorisation) are built once per model and reused; no file I/O.
#pragma once

#include <functional>
#include <vector>

#include <Eigen/Core>

#include "fem/model.hpp"
#include "fem/nodal_state.hpp"
#include "fem/static_solver.hpp"

namespace finverse::fem {

struct QuasiStaticInfo {
  int iterations = 0;
  int step_cuts = 0;
  double base_imbalance = 0;  // |f_int(x_t) - f_ext(t)| on the free DOFs / |f_ext(t+dt) - f_ext(t)|
};

class QuasiStaticIncrement {
 public:
  // options.steps load sub-steps per increment (1 suffices for the small increments of eq. (2);
  // the solver cuts steps itself when Newton fails).
  QuasiStaticIncrement(const Model& model, StaticOptions options = {.steps = 1});

  // x_{t+dt} from the base x_t; base is not modified. load_change (full length, optional): a
  // known change of load over the increment that the model's f_ext does not hold, e.g. the
  // inertial -M (a(t_next) - a(t)) of a measured motion (eq. (2) with inertia, issue 45).
  // Throws NotConverged / SingularMatrix / InvalidInput (see static_solver.hpp).
  NodalState solve(const NodalState& base, double t, double t_next, QuasiStaticInfo* info = nullptr,
                   const Eigen::VectorXd* load_change = nullptr);

  // dx = positions of solve() minus those of the base, [node][xyz]: the quantity eq. (2) compares.
  std::vector<Vec3> displacement_increment(const NodalState& base, double t, double t_next,
                                           QuasiStaticInfo* info = nullptr,
                                           const Eigen::VectorXd* load_change = nullptr);

  // The base's out-of-balance force that solve() takes as equilibrium, full length:
  // f_ext(t) - f_int(x_t) - load_change. solve() balances f_int(x) = f_ext(t_next) - offset.
  Eigen::VectorXd base_offset(const NodalState& base, double t, const Eigen::VectorXd* load_change = nullptr);

  StaticSolver& solver() { return solver_; }

 private:
  StaticSolver solver_;
};

// The driver: marches eq. (2) over the given times, each increment based on the previous result.
// states[0] = start (taken to be in equilibrium at times[0]); on_frame(k, state) is called after
// every increment (k = 1..n-1) if given.
std::vector<NodalState> march_quasi_static(QuasiStaticIncrement& increment, const NodalState& start,
                                           const std::vector<double>& times,
                                           const std::function<void(int, const NodalState&)>& on_frame = {});

}  // namespace finverse::fem
