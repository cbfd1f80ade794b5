// Load-controlled Newton-Raphson with step cutting (see static_solver.hpp).
#include "fem/static_solver.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "fem/errors.hpp"
#include "fem/newton_iteration.hpp"
#include "fem/rotation.hpp"

namespace finverse::fem {

std::string describe_dof(int g) {
  static const char* names[] = {"ux", "uy", "uz", "rx", "ry", "rz"};
  return "node " + std::to_string(g / kDofsPerNode) + " " + names[g % kDofsPerNode];
}

std::string describe_equation(const DofMap& dofs, int eq) {
  if (eq < 0 || eq >= dofs.free()) return "equation " + std::to_string(eq);
  return describe_dof(dofs.free_to_global()[eq]);
}

void apply_prescribed(const Model& model, double t1, double t2, NodalState& state) {
  const int nn = model.node_count();
  std::vector<int> rot_count(nn, 0);
  for (const auto& p : model.prescribed())
    if (p.dof >= 3) ++rot_count[p.node];
  std::vector<Vec3> spin(nn, Vec3::Zero()), full_rotation(nn, Vec3::Zero());
  for (const auto& p : model.prescribed()) {
    const double v2 = p.at(t2);
    if (!std::isfinite(v2)) {
      std::ostringstream os;
      os << "prescribed value of " << describe_dof(kDofsPerNode * p.node + p.dof) << " at t = "
         << t2 << " is " << v2;
      throw InvalidInput(os.str());
    }
    if (p.dof < 3) {
      state.position[p.node](p.dof) = model.reference_positions()[p.node](p.dof) + v2;
    } else if (rot_count[p.node] == 3) {
      full_rotation[p.node](p.dof - 3) = v2;
    } else {
      spin[p.node](p.dof - 3) = v2 - p.at(t1);
    }
  }
  for (int n = 0; n < nn; ++n) {
    if (rot_count[n] == 3)
      state.rotation[n] = exp_so3(full_rotation[n]);
    else if (spin[n].squaredNorm() > 0)
      state.rotation[n] = exp_so3(spin[n]) * state.rotation[n];
  }
}

StaticSolver::StaticSolver(const Model& model, StaticOptions options)
    : model_(model),
      opt_(options),
      dofs_((model.validate(), model)),
      assembler_(model_, dofs_, options.unsymmetric_tangent),
      solver_(tangent_backend(options.backend, options.unsymmetric_tangent)),
      lchar_(model.characteristic_length()) {
  if (opt_.steps < 1) throw InvalidInput("static solver: steps must be >= 1");
  solver_.set_equation_names([this](int eq) { return describe_equation(dofs_, eq); });
}

int StaticSolver::newton(NodalState& state, double lam, const Eigen::VectorXd* offset,
                         double& residual) {
  Eigen::VectorXd f_ext = model_.external_load(lam);
  if (!f_ext.allFinite()) {
    for (int g = 0; g < f_ext.size(); ++g)
      if (!std::isfinite(f_ext(g))) {
        std::ostringstream os;
        os << "external load on " << describe_dof(g) << " is " << f_ext(g) << " at load factor "
           << lam;
        throw InvalidInput(os.str());
      }
  }
  if (offset) f_ext -= *offset;
  const NewtonOutcome out = newton_iterations(
      {opt_.max_iterations, opt_.residual_tolerance, opt_.increment_tolerance}, assembler_,
      [&](double& scale) { return out_of_balance(assembler_, state, lam, f_ext, 0.0, scale); },
      [&](const Eigen::VectorXd& r) -> std::optional<double> {
        solver_.factorize(assembler_.matrix(), "tangent stiffness");
        const Eigen::VectorXd du = solver_.solve(r);
        if (!du.allFinite()) return std::nullopt;
        const double inc = scaled_increment_norm(dofs_, du, lchar_);
        state.apply_increment(dofs_.scatter_free(du));
        return inc;
      });
  residual = out.residual;
  return out.iterations;
}

Eigen::VectorXd prescribed_increment(const DofMap& dofs, const NodalState& from, const NodalState& to) {
  const int nn = static_cast<int>(from.position.size());
  Eigen::VectorXd dp = Eigen::VectorXd::Zero(dofs.total());
  for (int n = 0; n < nn; ++n) {
    const int g0 = kDofsPerNode * n;
    bool any = false;
    for (int j = 0; j < kDofsPerNode; ++j) any = any || dofs.is_prescribed(g0 + j);
    if (!any) continue;
    const Vec3 du = to.position[n] - from.position[n];
    const Vec3 w = log_so3(to.rotation[n] * from.rotation[n].transpose());
    for (int j = 0; j < 3; ++j) {
      if (dofs.is_prescribed(g0 + j)) dp(g0 + j) = du(j);
      if (dofs.is_prescribed(g0 + 3 + j)) dp(g0 + 3 + j) = w(j);
    }
  }
  return dp;
}

int StaticSolver::predict_free(const NodalState& state, NodalState& trial, double lam) {
  // Increment of the prescribed DOFs (rotations as spatial spins, the convention of
  // NodalState::apply_increment).
  Eigen::VectorXd dp = prescribed_increment(dofs_, state, trial);
  const bool moved = (dp.array() != 0).any();
  if (!moved || dofs_.free() == 0) return 0;
  AssemblyRequest req;
  req.matrix = true;
  req.stiffness_times = &dp;
  req.time = lam;
  assembler_.assemble(state, req);
  try {
    solver_.factorize(assembler_.matrix(), "tangent stiffness");
  } catch (const SingularMatrix&) {
    return 0;  // e.g. the base sits at a limit point: leave the free DOFs to Newton
  }
  const Eigen::VectorXd du = solver_.solve(-dofs_.gather_free(assembler_.stiffness_product()));
  if (!du.allFinite()) return 0;
  trial.apply_increment(dofs_.scatter_free(du));
  return 1;
}

StaticResult StaticSolver::solve(NodalState& state, double lam0, double lam1,
                                 const Eigen::VectorXd* offset) {
  StaticResult result;
  const double step0 = (lam1 - lam0) / opt_.steps;
  double step = step0;
  double lam = lam0;
  while ((lam1 - lam) * (step0 > 0 ? 1 : -1) > 1e-14 * std::abs(lam1 - lam0)) {
    if (std::abs(step) > std::abs(lam1 - lam)) step = lam1 - lam;
    NodalState trial = state;
    const double target = lam + step;
    apply_prescribed(model_, lam, target, trial);
    const int predictor_its = predict_free(state, trial, target);
    double residual = 0;
    int its = newton(trial, target, offset, residual);
    if (its >= 0) its += predictor_its;
    if (its < 0) {
      result.total_iterations += opt_.max_iterations;
      ++result.step_cuts;
      step *= 0.5;
      if (std::abs(step) < opt_.min_step_fraction * std::abs(step0)) {
        std::ostringstream os;
        os.precision(4);
        os << "static Newton did not converge at load factor " << target << " (from " << lam
           << "): step cut " << result.step_cuts << " times down to " << 2 * step
           << ", last relative residual " << residual << " (tolerance "
           << opt_.residual_tolerance << ")";
        throw NotConverged(os.str());
      }
      continue;
    }
    state = std::move(trial);
    lam = target;
    result.total_iterations += its;
    result.steps.push_back({lam, its, residual});
    if (std::abs(step) < std::abs(step0)) step = std::min(1.5 * std::abs(step), std::abs(step0)) * (step0 > 0 ? 1 : -1);
  }
  // Reactions at the converged state.
  AssemblyRequest reaction_request;
  reaction_request.time = lam1;
  assembler_.assemble(state, reaction_request);
  Eigen::VectorXd f_ext = model_.external_load(lam1);
  if (offset) f_ext -= *offset;
  result.reaction = Eigen::VectorXd::Zero(dofs_.total());
  for (int g = 0; g < dofs_.total(); ++g)
    if (dofs_.is_prescribed(g)) result.reaction(g) = assembler_.internal_force()(g) - f_ext(g);
  return result;
}

}  // namespace finverse::fem
