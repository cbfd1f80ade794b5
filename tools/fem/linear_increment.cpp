// Eq. (2)'s increment linearised at its base (see linear_increment.hpp).
#include "fem/linear_increment.hpp"

#include "fem/dof_map.hpp"
#include "fem/errors.hpp"
#include "fem/static_solver.hpp"

namespace finverse::fem {

LinearIncrement::LinearIncrement(const std::vector<const Model*>& models, const std::vector<double>& nus,
                                 const NodalState& base, double t, double t_next, const Eigen::VectorXd* load_change) {
  if (models.empty() || !models[0]) throw InvalidInput("linear increment: no model");
  const Model& model = *models[0];
  // The drive's increment, as the static solver's predictor takes it.
  const DofMap dofs(model);
  NodalState moved = base;
  apply_prescribed(model, t, t_next, moved);
  dp_ = prescribed_increment(dofs, base, moved);
  basis_ = std::make_unique<TangentBasis>(models, nus, base, t_next, &dp_);
  Eigen::VectorXd change = model.external_load(t_next) - model.external_load(t);
  if (load_change) {
    if (load_change->size() != change.size())
      throw InvalidInput("linear increment: the load change has " + std::to_string(load_change->size()) +
                         " entries, the model " + std::to_string(change.size()));
    change += *load_change;
  }
  load_free_ = basis_->dofs().gather_free(change);
}

std::vector<Vec3> LinearIncrement::displacement_increment(const std::vector<double>& element_moduli, double nu,
                                                          Workspace& w) const {
  basis_->combine(element_moduli, nu, w.matrix, &w.kv, w.scratch);
  const DofMap& dofs = basis_->dofs();
  w.solver.set_equation_names([&dofs](int eq) { return describe_equation(dofs, eq); });
  w.solver.factorize(w.matrix, "tangent stiffness at the base");
  const Eigen::VectorXd du = w.solver.solve(load_free_ - dofs.gather_free(w.kv));
  const int nn = static_cast<int>(dp_.size() / kDofsPerNode);
  std::vector<Vec3> dx(nn, Vec3::Zero());
  for (int n = 0; n < nn; ++n)
    for (int j = 0; j < 3; ++j) {
      const int g = kDofsPerNode * n + j;
      const int eq = dofs.equation(g);
      dx[n](j) = eq >= 0 ? du(eq) : dp_(g);
    }
  return dx;
}

}  // namespace finverse::fem
