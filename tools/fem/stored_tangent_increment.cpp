// Eq. (2)'s increment from a reference solution on its stored tangent, Anderson-accelerated
// (see stored_tangent_increment.hpp).
#include "fem/stored_tangent_increment.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <deque>

#include "fem/dof_map.hpp"
#include "fem/errors.hpp"
#include "fem/newton_iteration.hpp"
#include "fem/static_solver.hpp"

namespace finverse::fem {

StoredTangentIncrement::StoredTangentIncrement(const std::vector<const Model*>& models, const std::vector<double>& nus,
                                               const NodalState& reference, double t_next, StoredTangentOptions options)
    : reference_(reference), opt_(options) {
  if (models.empty() || !models[0]) throw InvalidInput("stored-tangent increment: no model");
  if (opt_.max_iterations < 1 || opt_.history < 0)
    throw InvalidInput("stored-tangent increment: max_iterations must be >= 1 and history >= 0");
  basis_ = std::make_unique<TangentBasis>(models, nus, reference, t_next);
  lchar_ = models[0]->characteristic_length();
}

namespace {

// The relative out-of-balance force as out_of_balance (newton_iteration.hpp) measures it, from an
// internal force already assembled: |r_free| / max(|f_free|, |reaction|).
double relative_residual(const DofMap& dofs, const Eigen::VectorXd& f_int, const Eigen::VectorXd& f_target,
                         const Eigen::VectorXd& r_free, double& scale) {
  double reaction = 0;
  for (int g = 0; g < dofs.total(); ++g)
    if (dofs.is_prescribed(g)) reaction += (f_int(g) - f_target(g)) * (f_int(g) - f_target(g));
  scale = std::max({dofs.gather_free(f_target).norm(), std::sqrt(reaction), 1e-30});
  return r_free.norm() / scale;
}

// Units of the free DOFs for the mixing's least squares: translations over the model's length,
// rotations in radians, as scaled_increment_norm weighs them.
Eigen::VectorXd unit_weights(const DofMap& dofs, double lchar) {
  Eigen::VectorXd w(dofs.free());
  for (int i = 0; i < dofs.free(); ++i) w(i) = (dofs.free_to_global()[i] % kDofsPerNode) < 3 ? 1.0 / lchar : 1.0;
  return w;
}

}  // namespace

bool StoredTangentIncrement::solve(Assembler& assembler, double time, const std::vector<double>& element_moduli,
                                   double nu, const Eigen::VectorXd& f_target, NodalState& x, Workspace& w,
                                   StoredTangentInfo* info) const {
  const DofMap& dofs = basis_->dofs();
  if (assembler.dofs().free() != dofs.free() || assembler.dofs().total() != dofs.total())
    throw InvalidInput("stored-tangent increment: the model's DOFs differ from the basis's");
  basis_->combine(element_moduli, nu, w.matrix, nullptr, w.scratch);
  w.solver.set_equation_names([&dofs](int eq) { return describe_equation(dofs, eq); });
  w.solver.factorize(w.matrix, "stored tangent at the reference solution");
  const double floor = roundoff_force_floor(w.matrix, dofs, assembler.model().position_scale());
  const Eigen::VectorXd units = unit_weights(dofs, lchar_);

  x = reference_;
  StoredTangentInfo out;
  // Anderson mixing on u (the free DOFs' accumulated increment) with g = K^-1 r: the columns are
  // differences of successive g and u; the step is g minus their least-squares part.
  std::deque<Eigen::VectorXd> dg, du;
  Eigen::VectorXd g_prev, step_prev;
  double r0 = 0, rn_prev = 0;
  int since_refresh = 0;
  AssemblyRequest req;
  req.time = time;
  for (int it = 0; it < opt_.max_iterations; ++it) {
    assembler.assemble(x, req);
    const Eigen::VectorXd& f_int = assembler.internal_force();
    const Eigen::VectorXd r = dofs.gather_free(f_target - f_int);
    double scale = 1;
    const double rn = relative_residual(dofs, f_int, f_target, r, scale);
    out.residual = rn;
    if (!std::isfinite(rn)) break;
    if (it == 0) r0 = rn;
    if (it > 2 && rn > 1e3 * std::max(r0, 1e-12)) break;  // diverging: leave it to Newton
    // Converging too slowly on the factorised matrix: the true tangent here (a Newton step).
    const bool balanced = rn <= opt_.residual_tolerance + floor / scale;  // only the increment test left
    if (!balanced && since_refresh >= 2 && rn > opt_.refresh_ratio * rn_prev && out.refreshes < opt_.max_refreshes) {
      AssemblyRequest with_matrix = req;
      with_matrix.matrix = true;
      assembler.assemble(x, with_matrix);
      w.solver.factorize(assembler.matrix(), "tangent stiffness");
      dg.clear(), du.clear();
      since_refresh = 0;
      ++out.refreshes;
    }
    ++since_refresh;
    rn_prev = rn;
    const Eigen::VectorXd g = w.solver.solve(r);
    if (!g.allFinite()) break;
    Eigen::VectorXd step = g;
    if (since_refresh > 1 && opt_.history > 0) {
      dg.push_back(g - g_prev);
      du.push_back(step_prev);
      if (static_cast<int>(dg.size()) > opt_.history) dg.pop_front(), du.pop_front();
      const int m = static_cast<int>(dg.size());
      Eigen::MatrixXd G(g.size(), m);
      for (int c = 0; c < m; ++c) G.col(c) = units.cwiseProduct(dg[c]);
      const Eigen::VectorXd gamma = G.colPivHouseholderQr().solve(units.cwiseProduct(g));
      if (gamma.allFinite())
        for (int c = 0; c < m; ++c) step -= gamma(c) * (du[c] + dg[c]);
    }
    const double inc = scaled_increment_norm(dofs, step, lchar_);
    x.apply_increment(dofs.scatter_free(step));
    g_prev = g;
    step_prev = step;
    out.iterations = it + 1;
    if (balanced && inc <= opt_.increment_tolerance) {
      out.converged = true;
      break;
    }
  }
  if (info) *info = out;
  return out.converged;
}

}  // namespace finverse::fem
